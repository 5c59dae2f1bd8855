#pragma once
// Scene files for tests of commands that take --mesh and --path: the box room as room.obj and a
// short storyboard inside it as path.json (28 frames: a slow turn, a fast stop, a hold).

#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>

#include "scene/box_room.h"

namespace vt::test {

inline void writeBoxRoomScene(const std::filesystem::path& folder) {
  const Mesh room = boxRoom();
  std::ofstream obj(folder / "room.obj");
  for (const glm::vec3& p : room.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const glm::vec2& t : room.uvs) obj << "vt " << t.x << ' ' << t.y << '\n';
  for (size_t i = 0; i + 2 < room.indices.size(); i += 3) {
    obj << 'f';
    for (size_t k = 0; k < 3; ++k)
      obj << ' ' << room.indices[i + k] + 1 << '/' << room.indices[i + k] + 1;
    obj << '\n';
  }
  std::ofstream(folder / "path.json") << R"({"start": {"position": [6, 1.6, 4.5], "yaw": 60,
    "pitch": -5, "fov": 70}, "storyboard": [
    {"name": "turn", "kind": "slow rotation", "yaw": 30, "frames": 20},
    {"name": "stop", "kind": "fast rotation that stops", "yaw": -40, "frames": 2},
    {"kind": "hold", "frames": 6}]})";
}

}  // namespace vt::test
