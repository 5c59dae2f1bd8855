#pragma once
// A pinhole camera and the one place where world positions become clip-space positions, for both
// renderers (docs/design.md section 3: computed once on the CPU, handed to the oracle and to GL).
// OpenGL conventions: view space looks down -z, clip z in [-w, w], window y up.

#include <glm/glm.hpp>
#include <string>

#include "scene/clip_space_mesh.h"
#include "scene/mesh.h"

namespace vt {

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 3.0f};
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDegrees = 60.0f;
  float nearPlane = 0.05f;
  float farPlane = 1000.0f;
};

// The view-projection matrix for a viewport of `aspect` = width / height.
glm::mat4 viewProjection(const Camera& camera, float aspect);

// Every vertex of `mesh` transformed to clip space (float, GLM's matrix product), uv copied.
// `jitter` moves the image by that many pixels of the viewport (x right, y up), as engines jitter
// a reduced needbuffer from frame to frame; zero leaves the matrix as it is.
ClipSpaceMesh toClipSpace(const Mesh& mesh, const Camera& camera, Viewport viewport,
                          glm::vec2 jitter = glm::vec2(0.0f));

// "x,y,z:tx,ty,tz[:fov]" -> Camera; throws std::invalid_argument naming what is wrong (NaN and
// infinities included, and a target equal to the position).
Camera parseCamera(const std::string& text);

}  // namespace vt
