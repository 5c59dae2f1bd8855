#include "vt/oracle/scene.h"

#include "reference/api/api_internal.h"
#include "scene/camera.h"
#include "scene/obj_mesh.h"

namespace vt::oracle {

Scene sceneFromObj(const std::filesystem::path& obj, const Camera& camera, Viewport viewport) {
  return translatingErrors([&] {
    vt::Camera internal;
    internal.position = glm::vec3(camera.position[0], camera.position[1], camera.position[2]);
    internal.target = glm::vec3(camera.target[0], camera.target[1], camera.target[2]);
    internal.up = glm::vec3(camera.up[0], camera.up[1], camera.up[2]);
    internal.fovYDegrees = camera.fovYDegrees;
    internal.nearPlane = camera.nearPlane;
    internal.farPlane = camera.farPlane;
    const ClipSpaceMesh clip =
        toClipSpace(loadObjMesh(obj), internal, {viewport.width, viewport.height});
    Scene scene;
    scene.viewport = viewport;
    scene.vertices.reserve(clip.vertices.size());
    for (const vt::ClipVertex& v : clip.vertices)
      scene.vertices.push_back(
          {v.position.x, v.position.y, v.position.z, v.position.w, v.uv.x, v.uv.y});
    scene.indices = clip.indices;
    return scene;
  });
}

}  // namespace vt::oracle
