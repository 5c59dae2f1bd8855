#pragma once
// The one OBJ reader (tinyobjloader) behind both loaders: the plain mesh (scene/obj_mesh.h) and
// the textured scene with materials (scene/obj_scene.h). It reads every polygon as written, with
// its corners' positions and texture coordinates, and validates the indices; the loaders choose
// what a face that is not finite means. OBJ's v is flipped to t = 1 - v (t along the image's
// rows, as the virtual texture's).
//
// A polygon of n corners becomes n - 2 triangles fanned from its first corner, (0, c, c + 1):
// the order the corners are written in, for convex polygons as the format intends. Both loaders
// triangulate by fanTriangles, so one OBJ draws the same triangles whichever loader read it.

#include <tiny_obj_loader.h>

#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

struct ObjFace {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  int material = -1;    // index into ObjFaces::materials; -1: none
  size_t shape = 0;     // index into ObjFaces::shapes
  bool finite() const;  // at least three corners, every coordinate finite
};

struct ObjFaces {
  std::vector<ObjFace> faces;  // shapes in file order, faces in shape order
  std::vector<tinyobj::material_t> materials;
  std::vector<std::string> shapes;  // the shapes' names, for messages
};

// Throws InputError naming `path` for text tinyobjloader refuses, a face without texture
// coordinates, and an index out of range. `materials` serves `mtllib` lines (none: they are
// skipped and every face has material -1).
ObjFaces readObjFaces(std::string_view text, const std::filesystem::path& path,
                      tinyobj::MaterialReader* materials = nullptr);

// The fan's indices of a polygon of `corners` corners whose first corner is vertex `base`.
void fanTriangles(uint32_t base, uint32_t corners, std::vector<uint32_t>& indices);

}  // namespace vt
