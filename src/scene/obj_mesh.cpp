#include "scene/obj_mesh.h"

#include <string>

#include "common/error.h"
#include "common/input_file.h"
#include "scene/obj_faces.h"

namespace vt {

Mesh loadObjMesh(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "mesh not found");
  return parseObjMesh(readTextFile(path, "mesh"), path);
}

Mesh parseObjMesh(std::string_view text, const std::filesystem::path& path) {
  // No material reader: `mtllib` lines are skipped, the mesh needs no materials.
  const ObjFaces obj = readObjFaces(text, path);
  Mesh mesh;
  for (const ObjFace& face : obj.faces) {
    if (face.positions.size() < 3) continue;  // a point or a line draws nothing
    if (!face.finite())
      throw InputError(path,
                       "shape '" + obj.shapes[face.shape] + "' has a vertex that is not finite");
    fanTriangles(static_cast<uint32_t>(mesh.positions.size()),
                 static_cast<uint32_t>(face.positions.size()), mesh.indices);
    mesh.positions.insert(mesh.positions.end(), face.positions.begin(), face.positions.end());
    mesh.uvs.insert(mesh.uvs.end(), face.uvs.begin(), face.uvs.end());
  }
  if (mesh.indices.empty()) throw InputError(path, "the mesh has no triangles");
  return mesh;
}

}  // namespace vt
