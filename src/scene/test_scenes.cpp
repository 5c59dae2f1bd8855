#include "scene/test_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
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

// A textured wall with occluders well in front of it, in both draw orders: a panel drawn before
// the wall (without a depth test the wall would paint over it) and a box drawn after it, its faces
// toward the camera first (without a depth test its back faces would paint over them). The near
// plane at 0.5 keeps the window depths of wall, box and panel about 2^-7 apart, far beyond gl45's
// depth bound (84 units of 2^-23 plus 1/16 pixel of vertex movement): only pixels on the box's
// silhouette are left to either face.
NamedScene occluders() {
  NamedScene scene{"occluders", {}, {}};
  scene.camera.position = {0.4f, 0.6f, 3};
  scene.camera.target = {0, 0, -4};
  scene.camera.nearPlane = 1;
  scene.camera.farPlane = 20;
  addQuad(scene.mesh, {-2.2f, -1.2f, 0}, {1.6f, 0, 0}, {0, 1.4f, 0}, {0.55f, 0.1f}, {0.35f, 0},
          {0, 0.35f});  // the panel, 3 units from the camera
  addQuad(scene.mesh, {-6, -3.5f, -5}, {12, 0, 0}, {0, 7, 0}, {0, 0}, {1, 0}, {0, 1});  // the wall
  // A cube of side 1.4 turned 35 degrees about y and tilted 20 degrees about x, 4.5 units away.
  const glm::vec3 centre(1.3f, -0.2f, -1.5f);
  const float cy = std::cos(0.61f), sy = std::sin(0.61f), cx = std::cos(0.35f),
              sx = std::sin(0.35f);
  const glm::vec3 ex(cy, 0, -sy), ey(sy * sx, cx, cy * sx), ez(sy * cx, -sx, cy * cx);
  struct Face {
    glm::vec3 normal, u, v;
  };
  // u x v = the outward normal: each face is counter-clockwise seen from outside.
  std::vector<Face> faces = {{ez, ex, ey},  {-ez, ey, ex}, {ex, ey, ez},
                             {-ex, ez, ey}, {ey, ez, ex},  {-ey, ex, ez}};
  std::stable_partition(faces.begin(), faces.end(), [&](const Face& f) {
    return glm::dot(f.normal, scene.camera.position - (centre + 0.7f * f.normal)) > 0;
  });
  for (size_t k = 0; k < faces.size(); ++k) {
    const Face& f = faces[k];
    const glm::vec2 uv0(0.1f + 0.13f * static_cast<float>(k), 0.6f);
    addQuad(scene.mesh, centre + 0.7f * (f.normal - f.u - f.v), 1.4f * f.u, 1.4f * f.v, uv0,
            {0.12f, 0}, {0, 0.3f});
  }
  return scene;
}

// Two large quads through the origin crossing at an angle, one turned 30 degrees about y, the
// other 30 degrees about x: their intersection runs diagonally across the screen, and each hides
// the other on one side of it. Depth decides every pixel but a band about a pixel wide along the
// line, where gl45's depth bound leaves either quad.
NamedScene crossing() {
  NamedScene scene{"crossing", {}, {}};
  scene.camera.position = {0, 0, 5};
  scene.camera.target = {0, 0, 0};
  scene.camera.nearPlane = 1;
  scene.camera.farPlane = 20;
  const float c = std::cos(0.7854f), s = std::sin(0.7854f);
  const glm::vec3 ua(c, 0, -s), va(0, 1, 0), ub(1, 0, 0), vb(0, c, -s);
  addQuad(scene.mesh, -2.0f * ua - 2.0f * va, 4.0f * ua, 4.0f * va, {0.05f, 0.05f}, {0.5f, 0},
          {0, 0.5f});
  addQuad(scene.mesh, -2.0f * ub - 2.0f * vb, 4.0f * ub, 4.0f * vb, {0.95f, 0.45f}, {0, 0.5f},
          {-0.5f, 0});
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
  return {"room", "grazing", "horizon", "coplanar", "minified", "terrain", "occluders", "crossing"};
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
  if (name == "occluders") return occluders();
  if (name == "crossing") return crossing();
  std::string names;
  for (const std::string& known : testSceneNames())
    names.append(names.empty() ? "" : ", ").append(known);
  throw std::invalid_argument("scene '" + name + "' is not one of " + names);
}

std::vector<NamedScene> flythroughViews(const Mesh& mesh, const CameraPath& path, int every) {
  std::vector<NamedScene> views;
  for (int frame = 0; frame < path.frameCount(); frame += every) {
    char name[32];
    std::snprintf(name, sizeof name, "frame%04d", frame);
    views.push_back({name, mesh, path.at(frame)});
  }
  return views;
}

std::vector<NamedScene> namedSceneViews(const std::string& list) {
  std::vector<NamedScene> views;
  if (list == "all") {
    for (const std::string& name : testSceneNames()) views.push_back(testScene(name));
    return views;
  }
  std::stringstream names(list);
  for (std::string name; std::getline(names, name, ',');) views.push_back(testScene(name));
  return views;
}

}  // namespace vt
