#include "scene/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/input_file.h"

namespace vt {

Mesh loadObjMesh(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "mesh not found");
  return parseObjMesh(readTextFile(path, "mesh"), path);
}

Mesh parseObjMesh(std::string_view text, const std::filesystem::path& path) {
  tinyobj::attrib_t attributes;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  std::istringstream stream{std::string(text)};
  // No material reader: `mtllib` lines are skipped, the mesh needs no materials.
  if (!tinyobj::LoadObj(&attributes, &shapes, &materials, &warning, &error, &stream, nullptr,
                        /*triangulate=*/true, /*default_vcols_fallback=*/true))
    throw InputError(path, "cannot read OBJ: " + error);
  Mesh mesh;
  for (const auto& shape : shapes) {
    for (const auto& index : shape.mesh.indices) {
      if (index.texcoord_index < 0)
        throw InputError(path, "shape '" + shape.name + "' has a face without texture coordinates");
      const size_t v = static_cast<size_t>(index.vertex_index),
                   t = static_cast<size_t>(index.texcoord_index);
      if (3 * v + 2 >= attributes.vertices.size() || 2 * t + 1 >= attributes.texcoords.size())
        throw InputError(path, "shape '" + shape.name + "' has an index out of range");
      const glm::vec3 p(attributes.vertices[3 * v], attributes.vertices[3 * v + 1],
                        attributes.vertices[3 * v + 2]);
      const glm::vec2 uv(attributes.texcoords[2 * t], 1.0f - attributes.texcoords[2 * t + 1]);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
          !std::isfinite(uv.x) || !std::isfinite(uv.y))
        throw InputError(path, "shape '" + shape.name + "' has a vertex that is not finite");
      mesh.indices.push_back(static_cast<uint32_t>(mesh.positions.size()));
      mesh.positions.push_back(p);
      mesh.uvs.push_back(uv);
    }
  }
  if (mesh.indices.empty()) throw InputError(path, "the mesh has no triangles");
  return mesh;
}

}  // namespace vt
