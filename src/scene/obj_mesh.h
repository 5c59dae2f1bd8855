#pragma once
// Loads a triangle mesh with texture coordinates from a Wavefront OBJ file (scene/obj_faces.h:
// polygons fanned from their first corner). Texture coordinates are taken as virtual coordinates
// (s, t) with t along the texture's rows: OBJ's v is flipped (t = 1 - v), as OBJ images have v
// up. Faces without texture coordinates, indices out of range and vertices that are not finite
// are errors naming the file.

#include <filesystem>
#include <string_view>

#include "scene/mesh.h"

namespace vt {

Mesh loadObjMesh(const std::filesystem::path& path);

// The same for an OBJ's text held in memory, `path` naming it in errors. Materials play no part.
Mesh parseObjMesh(std::string_view text, const std::filesystem::path& path);

}  // namespace vt
