#include "scene/test_scenes.h"

#include <cmath>
#include <stdexcept>

#include "scene/box_room.h"
#include "scene/terrain.h"

namespace vt {
namespace {

// A quad from `origin` along `u` and `v` with texture coordinates from uv0 along du and dv.
void addQuad(Mesh& mesh, glm::vec3 origin, glm::vec3 u, glm::vec3 v, glm::vec2 uv0, glm::vec2 du,
             glm::vec2 dv) {
  const auto base = static_cast<uint32_t>(mesh.positions.size());
  for (const glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
    mesh.positions.push_back(origin + c.x * u + c.y * v);
    mesh.uvs.push_back(uv0 + c.x * du + c.y * dv);
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

NamedScene grazing() {
  NamedScene scene{"grazing", {}, {}};
  const double theta = 89.9 * 3.14159265358979 / 180.0;
  const glm::vec3 v(0, static_cast<float>(std::cos(theta)), static_cast<float>(-std::sin(theta)));
  addQuad(scene.mesh, -100.0f * glm::vec3(1, 0, 0) - 100.0f * v, {200, 0, 0}, 200.0f * v, {0, 0},
          {1, 0}, {0, 1});
  scene.camera.position = {0, 0, 40};
  scene.camera.target = {0, 0, 0};
  scene.camera.nearPlane = 0.01f;
  return scene;
}

NamedScene horizon() {
  NamedScene scene{"horizon", {}, {}};
  addQuad(scene.mesh, {-1e5f, 0, 1e5f}, {2e5f, 0, 0}, {0, 0, -2e5f}, {0, 1}, {1, 0}, {0, -1});
  scene.camera.position = {0, 1, 0};
  scene.camera.target = {0, 1.0f - static_cast<float>(std::tan(3.14159265358979 / 6) / 32), -1};
  scene.camera.farPlane = 1e7f;
  return scene;
}

NamedScene coplanar() {
  NamedScene scene{"coplanar", {}, {}};
  addQuad(scene.mesh, {-2, -1.5f, 0}, {4, 0, 0}, {0, 3, 0}, {0.1f, 0.1f}, {0.3f, 0}, {0, 0.3f});
  addQuad(scene.mesh, {-1, -1, 0}, {3, 0, 0}, {0, 2.5f, 0}, {0.6f, 0.6f}, {0.3f, 0}, {0, 0.3f});
  scene.camera.position = {0.3f, 0.2f, 3};
  scene.camera.target = {0, 0, 0};
  return scene;
}

NamedScene minified() {
  NamedScene scene{"minified", {}, {}};
  addQuad(scene.mesh, {-3, -1, -20}, {2, 0, 0}, {0, 2, 0}, {0, 0}, {1, 0},
          {0, 1});  // far, whole texture
  addQuad(scene.mesh, {0.2f, -1, -1.5f}, {1, 0, 0}, {0, 1.5f, 0}, {0.99f, 0.99f}, {0.01f, 0},
          {0, 0.01f});  // near corner
  scene.camera.position = {0, 0, 0};
  scene.camera.target = {0, 0, -1};
  return scene;
}

}  // namespace

std::vector<std::string> testSceneNames() {
  return {"room", "grazing", "horizon", "coplanar", "minified", "terrain"};
}

NamedScene testScene(const std::string& name) {
  if (name == "room") {
    return NamedScene{"room", boxRoom(), boxRoomCamera()};
  }
  if (name == "grazing") return grazing();
  if (name == "horizon") return horizon();
  if (name == "coplanar") return coplanar();
  if (name == "minified") return minified();
  if (name == "terrain") return {"terrain", heightmapTerrain({}), terrainCamera({})};
  throw std::invalid_argument("scene '" + name +
                              "' is not one of room, grazing, horizon, coplanar, minified");
}

}  // namespace vt
