#include "scene/camera_path.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/error.h"
#include "common/posix_file.h"

namespace vt {
namespace {

glm::vec3 lerp(glm::vec3 a, glm::vec3 b, float t) { return a + (b - a) * t; }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

CameraPath::CameraPath(std::vector<Keyframe> keyframes) : keyframes_(std::move(keyframes)) {
  if (keyframes_.empty()) throw std::invalid_argument("the path has no keyframes");
  for (size_t k = 0; k < keyframes_.size(); ++k) {
    const Keyframe& key = keyframes_[k];
    const std::string where = "keyframe " + std::to_string(k) + ": ";
    if (key.frame < 0)
      throw std::invalid_argument(where + "frame " + std::to_string(key.frame) + " is negative");
    if (k > 0 && key.frame <= keyframes_[k - 1].frame)
      throw std::invalid_argument(where + "frame " + std::to_string(key.frame) +
                                  " does not rise above " +
                                  std::to_string(keyframes_[k - 1].frame));
    if (!finite(key.camera.position) || !finite(key.camera.target) ||
        !std::isfinite(key.camera.fovYDegrees))
      throw std::invalid_argument(where + "a value is not finite");
    if (key.camera.position == key.camera.target)
      throw std::invalid_argument(where + "the target equals the position");
    if (!(key.camera.fovYDegrees > 0.0f && key.camera.fovYDegrees < 180.0f))
      throw std::invalid_argument(where + "the field of view must lie in (0, 180) degrees");
  }
}

CameraPath CameraPath::load(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open camera path");
  try {
    const nlohmann::json root = nlohmann::json::parse(in);
    std::vector<Keyframe> keyframes;
    for (const auto& entry : root.at("keyframes")) {
      Keyframe key;
      key.frame = entry.at("frame").get<int>();
      const auto vec = [](const nlohmann::json& v) {
        if (!v.is_array() || v.size() != 3) throw std::invalid_argument("expected [x, y, z]");
        return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
      };
      key.camera.position = vec(entry.at("position"));
      key.camera.target = vec(entry.at("target"));
      if (entry.contains("fov")) key.camera.fovYDegrees = entry["fov"].get<float>();
      keyframes.push_back(key);
    }
    return CameraPath(std::move(keyframes));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, std::string("not a camera path: ") + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

Camera CameraPath::at(int frame) const {
  if (frame <= keyframes_.front().frame) return keyframes_.front().camera;
  if (frame >= keyframes_.back().frame) return keyframes_.back().camera;
  size_t k = 1;
  while (keyframes_[k].frame < frame) ++k;
  const Keyframe &a = keyframes_[k - 1], &b = keyframes_[k];
  const float t = static_cast<float>(frame - a.frame) / static_cast<float>(b.frame - a.frame);
  Camera camera = a.camera;
  camera.position = lerp(a.camera.position, b.camera.position, t);
  camera.target = lerp(a.camera.target, b.camera.target, t);
  camera.fovYDegrees = a.camera.fovYDegrees + (b.camera.fovYDegrees - a.camera.fovYDegrees) * t;
  return camera;
}

CameraPath boxRoomPath() {
  const auto key = [](int frame, glm::vec3 position, glm::vec3 target) {
    Keyframe k;
    k.frame = frame;
    k.camera.position = position;
    k.camera.target = target;
    k.camera.fovYDegrees = 70.0f;
    return k;
  };
  return CameraPath({key(0, {7.2f, 1.7f, 5.3f}, {1.0f, 1.0f, 0.8f}),     // the default view
                     key(20, {6.0f, 1.6f, 4.5f}, {0.5f, 1.2f, 4.0f}),    // slow turn left
                     key(30, {6.0f, 1.6f, 4.5f}, {0.5f, 1.2f, 4.0f}),    // stop
                     key(32, {6.0f, 1.6f, 4.5f}, {7.5f, 1.0f, 0.2f}),    // fast turn right
                     key(50, {2.0f, 1.5f, 3.0f}, {7.5f, 1.0f, 0.2f})});  // walk across
}

void saveCameraPath(const std::filesystem::path& file, const std::vector<Keyframe>& keyframes) {
  nlohmann::json frames = nlohmann::json::array();
  for (const Keyframe& k : keyframes)
    frames.push_back({{"frame", k.frame},
                      {"position", {k.camera.position.x, k.camera.position.y, k.camera.position.z}},
                      {"target", {k.camera.target.x, k.camera.target.y, k.camera.target.z}},
                      {"fov", k.camera.fovYDegrees}});
  const std::string text = nlohmann::json{{"keyframes", frames}}.dump(1) + "\n";
  writeFileAtomically(file, text);
}

}  // namespace vt
