#include "scene/box_room.h"

#include <array>

namespace vt {
namespace {

// Texel rectangles of the default scene's 4096^2 texture (build/demo_scene.cpp).
struct Area {
  float x, y, width, height;
};
constexpr float kSide = 4096.0f;
constexpr Area kBricks{100, 100, 1200, 700}, kPlanks{1500, 200, 900, 900},
    kTiles{2600, 1300, 700, 520}, kSky{300, 2100, 1800, 300}, kMarble{3300, 3500, 640, 470};

// A quad from corner `origin` along `u` and `v`, textured with `area` (u along s, v along t),
// inset by half a texel so that bilinear filtering stays inside the area.
void addQuad(Mesh& mesh, glm::vec3 origin, glm::vec3 u, glm::vec3 v, Area area) {
  const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
  const std::array<glm::vec2, 4> corners = {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1),
                                            glm::vec2(0, 1)};
  for (const glm::vec2 c : corners) {
    mesh.positions.push_back(origin + c.x * u + c.y * v);
    const float s = (area.x + 0.5f + c.x * (area.width - 1.0f)) / kSide;
    const float t = (area.y + 0.5f + c.y * (area.height - 1.0f)) / kSide;
    mesh.uvs.emplace_back(s, t);
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

}  // namespace

Mesh boxRoom() {
  Mesh mesh;
  const float w = 8.0f, h = 3.0f, d = 6.0f;
  // Faces seen from inside the room (counter-clockwise from inside).
  addQuad(mesh, {0, 0, d}, {w, 0, 0}, {0, 0, -d}, kPlanks);   // floor
  addQuad(mesh, {0, h, 0}, {w, 0, 0}, {0, 0, d}, kSky);       // ceiling
  addQuad(mesh, {0, h, 0}, {w, 0, 0}, {0, -h, 0}, kBricks);   // back wall (z = 0)
  addQuad(mesh, {w, h, d}, {-w, 0, 0}, {0, -h, 0}, kBricks);  // front wall (z = d)
  addQuad(mesh, {0, h, d}, {0, 0, -d}, {0, -h, 0}, kTiles);   // left wall (x = 0)
  addQuad(mesh, {w, h, 0}, {0, 0, d}, {0, -h, 0}, kMarble);   // right wall (x = w)
  return mesh;
}

Camera boxRoomCamera() {
  Camera camera;
  camera.position = {7.2f, 1.7f, 5.3f};
  camera.target = {1.0f, 1.0f, 0.8f};
  camera.fovYDegrees = 70.0f;
  return camera;
}

}  // namespace vt
