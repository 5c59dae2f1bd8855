#include "scene/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace vt {

glm::mat4 viewProjection(const Camera& camera, float aspect) {
  const glm::mat4 view = glm::lookAt(camera.position, camera.target, camera.up);
  const glm::mat4 projection =
      glm::perspective(glm::radians(camera.fovYDegrees), aspect, camera.nearPlane, camera.farPlane);
  return projection * view;
}

ClipSpaceMesh toClipSpace(const Mesh& mesh, const Camera& camera, Viewport viewport,
                          glm::vec2 jitter) {
  glm::mat4 matrix = viewProjection(
      camera, static_cast<float>(viewport.width) / static_cast<float>(viewport.height));
  if (jitter != glm::vec2(0.0f)) {
    // x_clip += (2 jx / W) w_clip: the window position moves by jx pixels.
    const glm::vec2 ndc = 2.0f * jitter / glm::vec2(viewport.width, viewport.height);
    matrix = glm::translate(glm::mat4(1.0f), glm::vec3(ndc, 0.0f)) * matrix;
  }
  ClipSpaceMesh clip;
  clip.vertices.reserve(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    clip.vertices.push_back({matrix * glm::vec4(mesh.positions[v], 1.0f), mesh.uvs[v]});
  clip.indices = mesh.indices;
  return clip;
}

Camera parseCamera(const std::string& text) {
  std::vector<std::vector<float>> groups;
  std::stringstream stream(text);
  std::string group;
  while (std::getline(stream, group, ':')) {
    std::vector<float> values;
    std::stringstream numbers(group);
    std::string number;
    while (std::getline(numbers, number, ',')) {
      size_t used = 0;
      float value = 0.0f;
      try {
        value = std::stof(number, &used);
      } catch (const std::exception&) {
        throw std::invalid_argument("camera: '" + number + "' is not a number");
      }
      if (used != number.size() || !std::isfinite(value))
        throw std::invalid_argument("camera: '" + number + "' is not a finite number");
      values.push_back(value);
    }
    groups.push_back(values);
  }
  if (groups.size() < 2 || groups.size() > 3 || groups[0].size() != 3 || groups[1].size() != 3 ||
      (groups.size() == 3 && groups[2].size() != 1))
    throw std::invalid_argument("camera: expected x,y,z:tx,ty,tz[:fov], got '" + text + "'");
  Camera camera;
  camera.position = {groups[0][0], groups[0][1], groups[0][2]};
  camera.target = {groups[1][0], groups[1][1], groups[1][2]};
  if (groups.size() == 3) camera.fovYDegrees = groups[2][0];
  if (camera.position == camera.target)
    throw std::invalid_argument("camera: the target equals the position");
  if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f))
    throw std::invalid_argument("camera: the field of view must lie in (0, 180) degrees");
  return camera;
}

}  // namespace vt
