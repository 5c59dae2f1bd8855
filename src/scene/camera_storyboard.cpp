#include "scene/camera_storyboard.h"

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/resource_limits.h"

namespace vt {
namespace {

glm::vec3 vec3Of(const nlohmann::json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw std::invalid_argument(where + ": expected [x, y, z]");
  return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
}

float numberOf(const nlohmann::json& motion, const char* key, float fallback,
               const std::string& where) {
  if (!motion.contains(key)) return fallback;
  if (!motion[key].is_number()) throw std::invalid_argument(where + ": '" + key + "' is no number");
  const float value = motion[key].get<float>();
  if (!std::isfinite(value)) throw std::invalid_argument(where + ": '" + key + "' is not finite");
  return value;
}

void checkKeys(const nlohmann::json& motion, std::initializer_list<const char*> allowed,
               const std::string& where) {
  for (const auto& [key, value] : motion.items()) {
    bool known = key == "name" || key == "kind" || key == "frames";
    for (const char* a : allowed) known = known || key == a;
    if (!known) throw std::invalid_argument(where + ": unknown key '" + key + "'");
  }
}

}  // namespace

CameraPath expandStoryboard(const nlohmann::json& document) {
  if (!document.is_object() || !document.contains("start") || !document.contains("storyboard"))
    throw std::invalid_argument("a storyboard needs 'start' and 'storyboard'");
  const nlohmann::json& start = document["start"];
  const nlohmann::json& motions = document["storyboard"];
  if (!motions.is_array() || motions.empty())
    throw std::invalid_argument("the storyboard has no motions");

  Keyframe pose;
  pose.camera.position = vec3Of(start.at("position"), "start: position");
  pose.camera.fovYDegrees = numberOf(start, "fov", 60.0f, "start");
  glm::vec2 angles(numberOf(start, "yaw", 0.0f, "start"), numberOf(start, "pitch", 0.0f, "start"));
  const auto place = [&](Keyframe& key) {
    key.yawPitch = angles;
    key.camera.target = key.camera.position + viewDirection(angles);
  };
  place(pose);
  std::vector<Keyframe> keyframes{pose};
  std::vector<NamedMotion> named;

  for (size_t m = 0; m < motions.size(); ++m) {
    const nlohmann::json& motion = motions[m];
    const std::string where =
        "motion " + std::to_string(m + 1) +
        (motion.is_object() && motion.contains("name") && motion["name"].is_string()
             ? " ('" + motion["name"].get<std::string>() + "')"
             : std::string());
    if (!motion.is_object() || !motion.contains("kind") || !motion["kind"].is_string())
      throw std::invalid_argument(where + ": needs a 'kind'");
    const std::string kind = motion["kind"].get<std::string>();
    if (!isMotionKind(kind)) throw std::invalid_argument(where + ": unknown kind '" + kind + "'");
    const float framesValue = numberOf(motion, "frames", 0.0f, where);
    if (!(framesValue >= 1.0f && framesValue <= 1e6f) || framesValue != std::floor(framesValue))
      throw std::invalid_argument(where + ": 'frames' must be a whole number from 1 to 1000000");
    const int frames = static_cast<int>(framesValue);

    const Keyframe from = keyframes.back();
    Keyframe to = from;
    // The sum of many motions could leave int; the path's own limit is far below it.
    if (int64_t{from.frame} + frames >= kMaxCameraPathFrames)
      throw std::invalid_argument(
          where + ": ends at frame " + std::to_string(int64_t{from.frame} + frames) +
          ", beyond the limit of " + std::to_string(kMaxCameraPathFrames - 1));
    to.frame = from.frame + frames;
    glm::vec2 turn(0.0f);
    if (kind == "hold") {
      checkKeys(motion, {}, where);
    } else if (kind == "corridor walk") {
      checkKeys(motion, {"distance"}, where);
      const float distance = numberOf(motion, "distance", 0.0f, where);
      glm::vec3 ahead = viewDirection({angles.x, 0.0f});
      to.camera.position += ahead * distance;
    } else if (kind == "translation") {
      checkKeys(motion, {"move", "yaw", "pitch"}, where);
      const glm::vec3 move = vec3Of(motion.at("move"), where + ": move");
      const glm::vec3 forward = viewDirection(angles);
      const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
      const glm::vec3 up = glm::cross(right, forward);
      to.camera.position += right * move.x + up * move.y + forward * move.z;
      turn = {numberOf(motion, "yaw", 0.0f, where), numberOf(motion, "pitch", 0.0f, where)};
    } else {  // the rotations
      checkKeys(motion, {"yaw", "pitch"}, where);
      turn = {numberOf(motion, "yaw", 0.0f, where), numberOf(motion, "pitch", 0.0f, where)};
      const float perFrame =
          std::max(std::abs(turn.x), std::abs(turn.y)) / static_cast<float>(frames);
      const bool slow = kind == "slow rotation";
      if (slow && perFrame > kSlowDegreesPerFrame)
        throw std::invalid_argument(where + ": turns " + std::to_string(perFrame) +
                                    " degrees per frame, a slow rotation at most " +
                                    std::to_string(kSlowDegreesPerFrame));
      if (!slow && perFrame <= kSlowDegreesPerFrame)
        throw std::invalid_argument(where + ": turns " + std::to_string(perFrame) +
                                    " degrees per frame, a fast rotation more than " +
                                    std::to_string(kSlowDegreesPerFrame));
      if (kind == "fast rotation that stops" && m + 1 < motions.size() &&
          !(motions[m + 1].is_object() && motions[m + 1].value("kind", "") == "hold"))
        throw std::invalid_argument(where + ": a rotation that stops must be followed by a hold");
    }
    angles += turn;
    if (!(std::abs(angles.y) < 90.0f))
      throw std::invalid_argument(where + ": the pitch leaves (-90, 90) degrees");
    place(to);
    keyframes.push_back(to);
    if (kind != "hold" || motion.contains("name")) {
      NamedMotion label;
      label.name = motion.value("name", kind);
      label.kind = kind;
      label.first = from.frame;
      label.last = to.frame;
      named.push_back(label);
    }
  }
  return CameraPath(std::move(keyframes), std::move(named));
}

}  // namespace vt
