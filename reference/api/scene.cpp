#include "vt/oracle/scene.h"

#include "reference/api/api_internal.h"
#include "scene/camera.h"
#include "scene/obj_mesh.h"

namespace vt::oracle {

Scene publicScene(const ClipSpaceMesh& mesh, vt::Viewport viewport) {
  Scene scene{{viewport.width, viewport.height}, {}, mesh.indices};
  scene.vertices.reserve(mesh.vertices.size());
  for (const vt::ClipVertex& v : mesh.vertices)
    scene.vertices.push_back(
        {v.position.x, v.position.y, v.position.z, v.position.w, v.uv.x, v.uv.y});
  return scene;
}

Scene sceneFromObj(const std::filesystem::path& obj, const Camera& camera, Viewport viewport) {
  return translatingErrors([&] {
    vt::Camera internal;
    internal.position = glm::vec3(camera.position[0], camera.position[1], camera.position[2]);
    internal.target = glm::vec3(camera.target[0], camera.target[1], camera.target[2]);
    internal.up = glm::vec3(camera.up[0], camera.up[1], camera.up[2]);
    internal.fovYDegrees = camera.fovYDegrees;
    internal.nearPlane = camera.nearPlane;
    internal.farPlane = camera.farPlane;
    const vt::Viewport size{viewport.width, viewport.height};
    return publicScene(toClipSpace(loadObjMesh(obj), internal, size), size);
  });
}

}  // namespace vt::oracle
