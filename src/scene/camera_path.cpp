#include "scene/camera_path.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "scene/camera_storyboard.h"

namespace vt {
namespace {

glm::vec3 lerp(glm::vec3 a, glm::vec3 b, float t) { return a + (b - a) * t; }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

const char* const kMotionKinds[] = {
    "hold",         "translation", "slow rotation", "fast rotation", "fast rotation that stops",
    "corridor walk"};

// A frame number: a JSON integer that fits an int (converting 1e10 to int is undefined).
int frameOf(const nlohmann::json& value, const std::string& what) {
  const bool fits = value.is_number_unsigned()
                        ? value.get<uint64_t>() <= uint64_t{INT_MAX}
                        : value.is_number_integer() && value.get<int64_t>() >= INT_MIN &&
                              value.get<int64_t>() <= INT_MAX;
  if (!fits) throw std::invalid_argument(what + ": " + value.dump() + " is not a frame number");
  return value.get<int>();
}

glm::vec3 vec3Of(const nlohmann::json& v) {
  if (!v.is_array() || v.size() != 3) throw std::invalid_argument("expected [x, y, z]");
  return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
}

}  // namespace

bool isMotionKind(const std::string& kind) {
  for (const char* k : kMotionKinds)
    if (kind == k) return true;
  return false;
}

glm::vec3 viewDirection(glm::vec2 yawPitchDegrees) {
  const double yaw = glm::radians(static_cast<double>(yawPitchDegrees.x));
  const double pitch = glm::radians(static_cast<double>(yawPitchDegrees.y));
  // yaw 0 looks down -z; positive yaw turns left (towards -x), seen from above (+y).
  return glm::vec3(static_cast<float>(-std::sin(yaw) * std::cos(pitch)),
                   static_cast<float>(std::sin(pitch)),
                   static_cast<float>(-std::cos(yaw) * std::cos(pitch)));
}

glm::vec2 yawPitchOf(const Camera& camera) {
  const glm::dvec3 d = glm::normalize(glm::dvec3(camera.target - camera.position));
  return glm::vec2(static_cast<float>(glm::degrees(std::atan2(-d.x, -d.z))),
                   static_cast<float>(glm::degrees(std::asin(std::clamp(d.y, -1.0, 1.0)))));
}

CameraPath::CameraPath(std::vector<Keyframe> keyframes, std::vector<NamedMotion> motions)
    : keyframes_(std::move(keyframes)), motions_(std::move(motions)) {
  if (keyframes_.empty()) throw std::invalid_argument("the path has no keyframes");
  for (size_t k = 0; k < keyframes_.size(); ++k) {
    const Keyframe& key = keyframes_[k];
    const std::string where = "keyframe " + std::to_string(k) + ": ";
    if (key.frame < 0)
      throw std::invalid_argument(where + "frame " + std::to_string(key.frame) + " is negative");
    // Frames up to this one are rendered (common/resource_limits.h).
    if (key.frame >= kMaxCameraPathFrames)
      throw std::invalid_argument(where + "frame " + std::to_string(key.frame) + " asks for " +
                                  std::to_string(int64_t{key.frame} + 1) +
                                  " frames, the limit is " + std::to_string(kMaxCameraPathFrames));
    if (k > 0 && key.frame <= keyframes_[k - 1].frame)
      throw std::invalid_argument(where + "frame " + std::to_string(key.frame) +
                                  " does not rise above " +
                                  std::to_string(keyframes_[k - 1].frame));
    if (!finite(key.camera.position) || !finite(key.camera.target) ||
        !std::isfinite(key.camera.fovYDegrees) ||
        (key.yawPitch && !(std::isfinite(key.yawPitch->x) && std::isfinite(key.yawPitch->y))))
      throw std::invalid_argument(where + "a value is not finite");
    if (key.yawPitch && !(std::abs(key.yawPitch->y) < 90.0f))
      throw std::invalid_argument(where + "the pitch must lie in (-90, 90) degrees");
    if (key.camera.position == key.camera.target)
      throw std::invalid_argument(where + "the target equals the position");
    if (!(key.camera.fovYDegrees > 0.0f && key.camera.fovYDegrees < 180.0f))
      throw std::invalid_argument(where + "the field of view must lie in (0, 180) degrees");
  }
  for (const NamedMotion& motion : motions_) {
    const std::string where = "motion '" + motion.name + "': ";
    if (!isMotionKind(motion.kind))
      throw std::invalid_argument(where + "unknown kind '" + motion.kind + "'");
    if (motion.first < 0 || motion.first > motion.last || motion.last >= frameCount())
      throw std::invalid_argument(where + "frames " + std::to_string(motion.first) + " to " +
                                  std::to_string(motion.last) + " do not lie in the path's 0 to " +
                                  std::to_string(frameCount() - 1));
  }
}

CameraPath CameraPath::load(const std::filesystem::path& file) {
  return parse(readTextFile(file, "camera path"), file);
}

CameraPath CameraPath::parse(std::string_view text, const std::filesystem::path& file) {
  try {
    const nlohmann::json root = parseJsonText(text, file);
    if (root.contains("storyboard")) return expandStoryboard(root);
    std::vector<Keyframe> keyframes;
    for (const auto& entry : root.at("keyframes")) {
      Keyframe key;
      key.frame = frameOf(entry.at("frame"), "keyframe " + std::to_string(keyframes.size()));
      key.camera.position = vec3Of(entry.at("position"));
      if (entry.contains("fov")) key.camera.fovYDegrees = entry["fov"].get<float>();
      if (entry.contains("target") == (entry.contains("yaw") || entry.contains("pitch")))
        throw std::invalid_argument("keyframe " + std::to_string(keyframes.size()) +
                                    ": give either a target or yaw and pitch");
      if (entry.contains("target")) {
        key.camera.target = vec3Of(entry.at("target"));
      } else {
        key.yawPitch = glm::vec2(entry.at("yaw").get<float>(), entry.at("pitch").get<float>());
        key.camera.target = key.camera.position + viewDirection(*key.yawPitch);
      }
      keyframes.push_back(key);
    }
    std::vector<NamedMotion> motions;
    for (const auto& entry : root.value("motions", nlohmann::json::array())) {
      NamedMotion motion;
      motion.name = entry.at("name").get<std::string>();
      motion.kind = entry.at("kind").get<std::string>();
      motion.first = frameOf(entry.at("first"), "motion '" + motion.name + "': first");
      motion.last = frameOf(entry.at("last"), "motion '" + motion.name + "': last");
      motions.push_back(motion);
    }
    return CameraPath(std::move(keyframes), std::move(motions));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a camera path: " + jsonErrorText(e));
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
  if (a.yawPitch && b.yawPitch)
    camera.target = camera.position + viewDirection(*a.yawPitch + (*b.yawPitch - *a.yawPitch) * t);
  else
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

void saveCameraPath(const std::filesystem::path& file, const std::vector<Keyframe>& keyframes,
                    const std::vector<NamedMotion>& motions) {
  nlohmann::json frames = nlohmann::json::array();
  for (const Keyframe& k : keyframes) {
    nlohmann::json key = {
        {"frame", k.frame},
        {"position", {k.camera.position.x, k.camera.position.y, k.camera.position.z}},
        {"fov", k.camera.fovYDegrees}};
    if (k.yawPitch) {
      key["yaw"] = k.yawPitch->x;
      key["pitch"] = k.yawPitch->y;
    } else {
      key["target"] = {k.camera.target.x, k.camera.target.y, k.camera.target.z};
    }
    frames.push_back(key);
  }
  nlohmann::json root = {{"keyframes", frames}};
  if (!motions.empty()) {
    root["motions"] = nlohmann::json::array();
    for (const NamedMotion& m : motions)
      root["motions"].push_back(
          {{"name", m.name}, {"kind", m.kind}, {"first", m.first}, {"last", m.last}});
  }
  const std::string text = root.dump(1) + "\n";
  writeFileAtomically(file, text);
}

}  // namespace vt
