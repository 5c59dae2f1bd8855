#include "scene/obj_faces.h"

#include <cmath>
#include <sstream>
#include <string>

#include "common/error.h"

namespace vt {

bool ObjFace::finite() const {
  if (positions.size() < 3) return false;
  for (size_t c = 0; c < positions.size(); ++c)
    if (!std::isfinite(positions[c].x) || !std::isfinite(positions[c].y) ||
        !std::isfinite(positions[c].z) || !std::isfinite(uvs[c].x) || !std::isfinite(uvs[c].y))
      return false;
  return true;
}

namespace {

// The text without tinyobjloader's skin-weight statements (`vw`, an extension of its own that no
// scene here uses), each left as an empty line so that line numbers stay: it converts their joint
// ids from float to int unchecked, undefined behaviour past INT_MAX (found by fuzzing).
std::string withoutSkinWeights(std::string_view text) {
  std::string kept;
  kept.reserve(text.size());
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    end = end == std::string_view::npos ? text.size() : end + 1;
    const std::string_view line = text.substr(start, end - start);
    const size_t first = line.find_first_not_of(" \t");
    const bool weights = first != std::string_view::npos && line.size() > first + 2 &&
                         line.compare(first, 2, "vw") == 0 &&
                         (line[first + 2] == ' ' || line[first + 2] == '\t');
    if (weights)
      kept += '\n';
    else
      kept += line;
    start = end;
  }
  return kept;
}

}  // namespace

ObjFaces readObjFaces(std::string_view text, const std::filesystem::path& path,
                      tinyobj::MaterialReader* materials) {
  tinyobj::attrib_t attributes;
  std::vector<tinyobj::shape_t> shapes;
  ObjFaces result;
  std::string warning, error;
  std::istringstream stream{withoutSkinWeights(text)};
  if (!tinyobj::LoadObj(&attributes, &shapes, &result.materials, &warning, &error, &stream,
                        materials, /*triangulate=*/false, /*default_vcols_fallback=*/true))
    throw InputError(path, "cannot read OBJ: " + error);
  for (const tinyobj::shape_t& shape : shapes) {
    result.shapes.push_back(shape.name);
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t corners = shape.mesh.num_face_vertices[f];
      if (offset + corners > shape.mesh.indices.size())
        throw InputError(path, "shape '" + shape.name + "' has a face beyond its indices");
      ObjFace face;
      face.shape = result.shapes.size() - 1;
      face.material = shape.mesh.material_ids.size() > f ? shape.mesh.material_ids[f] : -1;
      for (size_t c = 0; c < corners; ++c) {
        const tinyobj::index_t& index = shape.mesh.indices[offset + c];
        if (index.texcoord_index < 0)
          throw InputError(path,
                           "shape '" + shape.name + "' has a face without texture coordinates");
        const auto v = static_cast<size_t>(index.vertex_index),
                   t = static_cast<size_t>(index.texcoord_index);
        if (index.vertex_index < 0 || 3 * v + 2 >= attributes.vertices.size() ||
            2 * t + 1 >= attributes.texcoords.size())
          throw InputError(path, "shape '" + shape.name + "' has an index out of range");
        face.positions.emplace_back(attributes.vertices[3 * v], attributes.vertices[3 * v + 1],
                                    attributes.vertices[3 * v + 2]);
        face.uvs.emplace_back(attributes.texcoords[2 * t], 1.0f - attributes.texcoords[2 * t + 1]);
      }
      offset += corners;
      result.faces.push_back(std::move(face));
    }
  }
  return result;
}

void fanTriangles(uint32_t base, uint32_t corners, std::vector<uint32_t>& indices) {
  for (uint32_t c = 1; c + 1 < corners; ++c)
    indices.insert(indices.end(), {base, base + c, base + c + 1});
}

}  // namespace vt
