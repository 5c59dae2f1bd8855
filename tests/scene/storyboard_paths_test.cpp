// The storyboards of data/paths on the real OpenArena maps they were drawn for: am_thornish (thesis
// 4.2.1's flythrough, motions 1 to 15), q3dm6ish (the same kinds of motion, short enough for CI)
// and islandctf (4.4's terrain flight over small hills). Each map is loaded with the Quake 3 loader
// and the path is checked against its triangles: the camera never passes through geometry, keeps
// 0.25 m from every triangle, looks at geometry rather than empty sky, and the walls, corridors and
// the ramp the motions name are where they say. Needs OpenArena (scripts/fetch-openarena.sh,
// VT_OPENARENA_DIR); skipped without it, except in CI.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "openarena_data.h"
#include "scene/camera_path.h"
#include "scene/obj_mesh.h"
#include "scene/package_files.h"
#include "scene/quake3_scene.h"
#include "test_support.h"

namespace vt {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr float kClearance = 0.25f;  // metres between the camera and every triangle
constexpr float kViewRange = 200.0f;

struct Triangle {
  glm::vec3 a, b, c;
  glm::vec3 normal() const { return glm::normalize(glm::cross(b - a, c - a)); }
};

// The closest point of a triangle to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::vec3 closestPoint(const Triangle& t, glm::vec3 p) {
  const glm::vec3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return t.a;
  const glm::vec3 bp = p - t.b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return t.b;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return t.a + ab * (d1 / (d1 - d3));
  const glm::vec3 cp = p - t.c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return t.c;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return t.a + ac * (d2 / (d2 - d6));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return t.b + (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const float scale = 1.0f / (va + vb + vc);
  return t.a + ab * (vb * scale) + ac * (vc * scale);
}

// Where o + s d meets the triangle, both sides counted, s >= 0 (Moller-Trumbore); infinity when
// it does not. The barycentric tolerance closes the cracks between neighbouring triangles.
float hitDistance(const Triangle& t, glm::vec3 o, glm::vec3 d) {
  constexpr float kSlack = 1e-5f;
  const glm::vec3 e1 = t.b - t.a, e2 = t.c - t.a, p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return kInfinity;
  const float inverse = 1.0f / det;
  const glm::vec3 s = o - t.a;
  const float u = glm::dot(s, p) * inverse;
  if (u < -kSlack || u > 1 + kSlack) return kInfinity;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) * inverse;
  if (v < -kSlack || u + v > 1 + kSlack) return kInfinity;
  const float distance = glm::dot(e2, q) * inverse;
  return distance >= 0 ? distance : kInfinity;
}

struct Box {
  glm::vec3 low{kInfinity}, high{-kInfinity};
  void add(glm::vec3 p) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  float distanceSquared(glm::vec3 p) const {
    const glm::vec3 outside = glm::max(glm::max(low - p, p - high), glm::vec3(0.0f));
    return glm::dot(outside, outside);
  }
  // Whether o + s d enters the box for some s in [0, range]; `inverse` is 1 / d.
  bool crossed(glm::vec3 o, glm::vec3 inverse, float range) const {
    const glm::vec3 t0 = (low - o) * inverse, t1 = (high - o) * inverse;
    const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
    const float enter = std::max({near.x, near.y, near.z, 0.0f});
    const float leave = std::min({far.x, far.y, far.z, range});
    return enter <= leave;
  }
};

struct Hit {
  float distance = kInfinity;
  int triangle = -1;
};

// A bounding-volume hierarchy over a map's triangles: nearest distance and ray casts.
class TriangleTree {
 public:
  explicit TriangleTree(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
    std::vector<int> order(triangles_.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    build(order, 0, static_cast<int>(order.size()));
    std::vector<Triangle> sorted;
    sorted.reserve(order.size());
    for (int i : order) sorted.push_back(triangles_[static_cast<size_t>(i)]);
    triangles_ = std::move(sorted);
  }

  const std::vector<Triangle>& triangles() const { return triangles_; }

  float nearestDistance(glm::vec3 p) const {
    float best = kInfinity;
    visit([&](const Node& node) { return node.box.distanceSquared(p) < best; },
          [&](const Triangle& t, int) {
            const glm::vec3 d = closestPoint(t, p) - p;
            best = std::min(best, glm::dot(d, d));
          });
    return std::sqrt(best);
  }

  // The first triangle on o + s d for s in [0, range] (d need not be a unit vector).
  Hit cast(glm::vec3 o, glm::vec3 d, float range) const {
    const glm::vec3 inverse = 1.0f / d;
    Hit hit;
    float reach = range;
    visit([&](const Node& node) { return node.box.crossed(o, inverse, reach); },
          [&](const Triangle& t, int index) {
            const float s = hitDistance(t, o, d);
            if (s <= reach) reach = s, hit = {s, index};
          });
    return hit;
  }

 private:
  struct Node {
    Box box;
    int first = 0, count = 0;  // a leaf's triangles; an inner node has count 0
    int left = 0, right = 0;
  };

  template <typename Enter, typename Leaf>
  void visit(Enter enter, Leaf leaf) const {
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& node = nodes_[static_cast<size_t>(stack.back())];
      stack.pop_back();
      if (!enter(node)) continue;
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i)
          leaf(triangles_[static_cast<size_t>(i)], i);
      } else {
        stack.push_back(node.left);
        stack.push_back(node.right);
      }
    }
  }

  int build(std::vector<int>& order, int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box box, centres;
    for (int i = begin; i < end; ++i) {
      const Triangle& t = triangles_[static_cast<size_t>(order[static_cast<size_t>(i)])];
      box.add(t.a), box.add(t.b), box.add(t.c);
      centres.add((t.a + t.b + t.c) / 3.0f);
    }
    nodes_[static_cast<size_t>(index)].box = box;
    if (end - begin <= 4) {
      nodes_[static_cast<size_t>(index)].first = begin;
      nodes_[static_cast<size_t>(index)].count = end - begin;
      return index;
    }
    const glm::vec3 extent = centres.high - centres.low;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const int middle = (begin + end) / 2;
    std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                     [&](int a, int b) {
                       const Triangle& ta = triangles_[static_cast<size_t>(a)];
                       const Triangle& tb = triangles_[static_cast<size_t>(b)];
                       return (ta.a + ta.b + ta.c)[axis] < (tb.a + tb.b + tb.c)[axis];
                     });
    const int left = build(order, begin, middle);
    const int right = build(order, middle, end);
    nodes_[static_cast<size_t>(index)].left = left;
    nodes_[static_cast<size_t>(index)].right = right;
    return index;
  }

  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

// A map's drawn triangles, in face order as `vt retexture` writes them to its OBJ.
std::vector<Triangle> loaderTriangles(const TexturedScene& scene) {
  std::vector<Triangle> triangles;
  for (const TexturedFace& face : scene.faces)
    for (uint32_t i = face.firstIndex; i + 2 < face.firstIndex + face.indexCount; i += 3)
      triangles.push_back({scene.positions[scene.indices[i]], scene.positions[scene.indices[i + 1]],
                           scene.positions[scene.indices[i + 2]]});
  return triangles;
}

// Each map once for the whole suite: the Quake 3 loader's triangles, and a tree over them.
struct LoadedMap {
  std::vector<Triangle> triangles;  // in face order
  TriangleTree tree;
};

const LoadedMap& loadMap(const std::filesystem::path& packages, const std::string& map) {
  static std::map<std::string, std::unique_ptr<LoadedMap>> maps;
  std::unique_ptr<LoadedMap>& loaded = maps[map];
  if (!loaded) {
    // One folder per process: ctest runs the suite's tests as processes side by side.
    const std::filesystem::path images =
        std::filesystem::temp_directory_path() /
        ("vt-storyboard-images-" + map + "-" + std::to_string(::getpid()));
    const TexturedScene scene = loadQuake3Map(PackageFiles::fromFolders({packages}), map, images);
    std::filesystem::remove_all(images);
    std::vector<Triangle> triangles = loaderTriangles(scene);
    loaded = std::make_unique<LoadedMap>(LoadedMap{triangles, TriangleTree(triangles)});
  }
  return *loaded;
}

std::filesystem::path storyboardFile(const std::string& map) {
  return std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data" / "paths" /
         (map + ".storyboard.json");
}

glm::vec3 forwardOf(const Camera& camera) {
  return glm::normalize(camera.target - camera.position);
}

// The fraction of a 16 x 9 grid of view rays (aspect 16:9) that meet a triangle within range.
float hitFraction(const TriangleTree& tree, const Camera& camera) {
  const glm::vec3 forward = forwardOf(camera);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanY = std::tan(glm::radians(camera.fovYDegrees) / 2.0f);
  const float tanX = tanY * 16.0f / 9.0f;
  constexpr int kColumns = 16, kRows = 9;
  int hits = 0;
  for (int row = 0; row < kRows; ++row)
    for (int column = 0; column < kColumns; ++column) {
      const float x = ((static_cast<float>(column) + 0.5f) / kColumns * 2.0f - 1.0f) * tanX;
      const float y = ((static_cast<float>(row) + 0.5f) / kRows * 2.0f - 1.0f) * tanY;
      const glm::vec3 ray = glm::normalize(forward + right * x + up * y);
      if (tree.cast(camera.position, ray, kViewRange).distance <= kViewRange) ++hits;
    }
  return static_cast<float>(hits) / (kColumns * kRows);
}

// How far a horizontal ray at yaw (degrees, the camera's convention) reaches from p.
float reachAt(const TriangleTree& tree, glm::vec3 p, float yawDegrees) {
  return tree.cast(p, viewDirection({yawDegrees, 0.0f}), 1e4f).distance;
}

struct MapPlan {
  std::string map;
  int minFrames, maxFrames;
  float minHitFraction;
  std::set<std::string> kinds;  // that must appear among the named motions
};

const std::set<std::string> kAllKinds = {"hold",          "translation",
                                         "slow rotation", "fast rotation",
                                         "corridor walk", "fast rotation that stops"};

// Lengths: the walks and translations move at a Quake 3 player's run speed at 30 frames a
// second and the slow turns at 2 degrees a frame (data/README.md), so that 5 pages a frame fall
// behind in ordinary motion (the regime of issue 19); am_thornish's fifteen motions then take
// about 360 frames, q3dm6ish's sixteen about 310.
std::vector<MapPlan> plans() {
  return {{"am_thornish",
           300,
           900,
           0.5f,
           {"translation", "slow rotation", "fast rotation", "corridor walk",
            "fast rotation that stops"}},
          {"q3dm6ish", 200, 400, 0.5f, kAllKinds},
          {"islandctf", 300, 600, 0.3f, {"translation"}}};
}

void PrintTo(const MapPlan& plan, std::ostream* out) { *out << plan.map; }

class StoryboardPaths : public ::testing::TestWithParam<MapPlan> {};

std::string planName(const ::testing::TestParamInfo<MapPlan>& info) { return info.param.map; }

// `vt retexture` writes the OBJ that `vt fly` flies through: its triangles are the loader's,
// in the same coordinates (quake_axes.h), so the checks below hold for the flown scene.
TEST_P(StoryboardPaths, RetexturedObjHasTheLoadersCoordinates) {
  VT_REQUIRE_OPENARENA(packages);
  const std::string map = GetParam().map;
  test::ScratchDirectory dir;
  const test::CommandResult result =
      test::runCommand(VT_EXECUTABLE,
                       {"retexture", map, "--packages", packages->string(), "-o",
                        (dir / "out").string(), "--no-coherence"},
                       dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  const Mesh mesh = loadObjMesh(dir / "out" / (map + ".obj"));
  const std::vector<Triangle>& loader = loadMap(*packages, map).triangles;
  ASSERT_EQ(mesh.indices.size(), loader.size() * 3);
  float worst = 0.0f;
  for (size_t t = 0; t < loader.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      const glm::vec3 obj = mesh.positions[mesh.indices[t * 3 + k]];
      const glm::vec3 own = k == 0 ? loader[t].a : k == 1 ? loader[t].b : loader[t].c;
      worst = std::max(worst, glm::length(obj - own));
    }
  EXPECT_LT(worst, 1e-5f) << "metres between an OBJ vertex and the loader's";
}

TEST_P(StoryboardPaths, ExpandsWithTheRequiredMotionsAndLength) {
  const MapPlan& plan = GetParam();
  std::optional<CameraPath> expanded;
  ASSERT_NO_THROW(expanded.emplace(CameraPath::load(storyboardFile(plan.map))));
  const CameraPath& path = *expanded;
  EXPECT_GE(path.frameCount(), plan.minFrames);
  EXPECT_LE(path.frameCount(), plan.maxFrames);
  std::set<std::string> kinds;
  for (const NamedMotion& motion : path.motions()) kinds.insert(motion.kind);
  for (const std::string& kind : plan.kinds) EXPECT_TRUE(kinds.count(kind)) << kind;
  for (int frame = 0; frame < path.frameCount(); ++frame) {
    const Camera camera = path.at(frame);
    ASSERT_TRUE(std::isfinite(camera.position.x + camera.position.y + camera.position.z));
  }
}

// Thesis 4.2.1's storyboard: motions 1 to 15 in order, each of the kind the thesis describes.
TEST(StoryboardPathsAmThornish, MotionsAreTheThesisFifteenInOrder) {
  const CameraPath path = CameraPath::load(storyboardFile("am_thornish"));
  const std::array<const char*, 15> kinds = {
      "fast rotation that stops",  // 1
      "translation",               // 2
      "slow rotation",             // 3
      "slow rotation",             // 4
      "slow rotation",             // 5
      "translation",               // 6
      "translation",               // 7
      "fast rotation",             // 8
      "fast rotation",             // 9
      "fast rotation",             // 10
      "corridor walk",             // 11
      "corridor walk",             // 12
      "slow rotation",             // 13
      "slow rotation",             // 14
      "translation",               // 15
  };
  ASSERT_EQ(path.motions().size(), kinds.size());
  for (size_t m = 0; m < kinds.size(); ++m) {
    const NamedMotion& motion = path.motions()[m];
    const std::string number = std::to_string(m + 1);
    EXPECT_EQ(motion.name.substr(0, number.size() + 2), number + ": ") << motion.name;
    EXPECT_GT(motion.name.size(), number.size() + 2) << "a description after the number";
    EXPECT_EQ(motion.kind, kinds[m]) << motion.name;
  }
  // Motion 1 turns in one frame and the camera then stands still (a short hold).
  const NamedMotion& first = path.motions().front();
  EXPECT_EQ(first.last - first.first, 1);
  const Camera stopped = path.at(first.last);
  for (int frame = first.last + 1; frame <= first.last + 5; ++frame) {
    EXPECT_EQ(path.at(frame).position, stopped.position);
    EXPECT_EQ(path.at(frame).target, stopped.target);
  }
  // Motion 8 to 10 turn quite fast about y and very slowly about x.
  for (size_t m = 7; m < 10; ++m) {
    const NamedMotion& motion = path.motions()[m];
    glm::vec2 turn = yawPitchOf(path.at(motion.last)) - yawPitchOf(path.at(motion.first));
    turn.x = std::remainder(turn.x, 360.0f);  // the shorter way round
    const float frames = static_cast<float>(motion.last - motion.first);
    EXPECT_GT(std::abs(turn.x) / frames, 2.0f) << motion.name;
    EXPECT_LT(std::abs(turn.y) / frames, 0.5f) << motion.name;
  }
}

// The terrain flight translates without turning: every frame looks the way the first does.
TEST(StoryboardPathsIslandctf, FlightTranslatesWithoutRotation) {
  const CameraPath path = CameraPath::load(storyboardFile("islandctf"));
  const glm::vec3 view = forwardOf(path.at(0));
  EXPECT_LT(view.y, 0.0f) << "the flight looks down at the terrain ahead";
  float travelled = 0.0f;
  for (int frame = 1; frame < path.frameCount(); ++frame) {
    EXPECT_GT(glm::dot(forwardOf(path.at(frame)), view), 0.99999f) << "frame " << frame;
    travelled += glm::length(path.at(frame).position - path.at(frame - 1).position);
  }
  EXPECT_GT(travelled, 50.0f) << "metres over the island";
}

// Every frame keeps kClearance from every triangle and the step from the previous frame crosses
// none; the view rays meet geometry (no long looks at empty sky).
TEST_P(StoryboardPaths, CameraKeepsClearOfGeometryAndSeesIt) {
  VT_REQUIRE_OPENARENA(packages);
  const MapPlan& plan = GetParam();
  const TriangleTree& tree = loadMap(*packages, plan.map).tree;
  const CameraPath path = CameraPath::load(storyboardFile(plan.map));
  float nearest = kInfinity, leastSeen = 1.0f;
  int nearestFrame = 0, leastSeenFrame = 0;
  for (int frame = 0; frame < path.frameCount(); ++frame) {
    const Camera camera = path.at(frame);
    const float distance = tree.nearestDistance(camera.position);
    if (distance < nearest) nearest = distance, nearestFrame = frame;
    if (frame > 0) {
      const glm::vec3 from = path.at(frame - 1).position;
      if (from != camera.position) {
        EXPECT_GT(tree.cast(from, camera.position - from, 1.0f).distance, 1.0f)
            << "the step to frame " << frame << " passes through a triangle";
      }
    }
    const float seen = hitFraction(tree, camera);
    if (seen < leastSeen) leastSeen = seen, leastSeenFrame = frame;
  }
  EXPECT_GE(nearest, kClearance) << "metres from a triangle at frame " << nearestFrame;
  EXPECT_GE(leastSeen, plan.minHitFraction) << "of the view rays hit at frame " << leastSeenFrame;
}

// A corridor walk goes where the corridor is: the way ahead is open for the rest of the walk, and a
// wall runs beside the camera (within 3.5 m, left or right) for two thirds of the way or more
// (doorways and the junction at its end aside).
TEST_P(StoryboardPaths, CorridorWalksRunBetweenWalls) {
  VT_REQUIRE_OPENARENA(packages);
  const MapPlan& plan = GetParam();
  const TriangleTree& tree = loadMap(*packages, plan.map).tree;
  const CameraPath path = CameraPath::load(storyboardFile(plan.map));
  for (const NamedMotion& motion : path.motions()) {
    if (motion.kind != "corridor walk") continue;
    const glm::vec3 end = path.at(motion.last).position;
    int walled = 0;
    for (int frame = motion.first; frame <= motion.last; ++frame) {
      const Camera camera = path.at(frame);
      const float yaw = yawPitchOf(camera).x;
      const float ahead = reachAt(tree, camera.position, yaw);
      EXPECT_GT(ahead, glm::length(end - camera.position) + kClearance)
          << motion.name << ", frame " << frame;
      const float beside = std::min(reachAt(tree, camera.position, yaw + 90.0f),
                                    reachAt(tree, camera.position, yaw - 90.0f));
      if (beside < 3.5f) ++walled;
    }
    EXPECT_GE(static_cast<float>(walled),
              2.0f / 3.0f * static_cast<float>(motion.last - motion.first + 1))
        << motion.name << ": frames with a wall beside";
  }
}

// am_thornish: 6 ends at the wall in front, 7 slides sideways along it (the wall stays in front),
// and 15 ends at the foot of a ramp (a sloped surface ahead); 11 and 12 are checked as corridor
// walks above.
TEST(StoryboardPathsAmThornish, WallsAndTheRampAreWhereTheMotionsSay) {
  VT_REQUIRE_OPENARENA(packages);
  const TriangleTree& tree = loadMap(*packages, "am_thornish").tree;
  const CameraPath path = CameraPath::load(storyboardFile("am_thornish"));
  ASSERT_EQ(path.motions().size(), 15u);
  const auto ahead = [&](int frame) {
    const Camera camera = path.at(frame);
    return tree.cast(camera.position, forwardOf(camera), 1e4f).distance;
  };
  const NamedMotion& toWall = path.motions()[5];
  EXPECT_GT(ahead(toWall.first), ahead(toWall.last) + 0.5f) << "6 moves towards the wall";
  EXPECT_LT(ahead(toWall.last), 2.0f) << "6 ends at the wall";
  const NamedMotion& alongWall = path.motions()[6];
  const glm::vec3 slide = path.at(alongWall.last).position - path.at(alongWall.first).position;
  EXPECT_GT(glm::length(slide), 3.0f);
  EXPECT_LT(std::abs(glm::dot(glm::normalize(slide), forwardOf(path.at(alongWall.first)))), 0.01f)
      << "7 moves sideways";
  for (int frame = alongWall.first; frame <= alongWall.last; ++frame)
    EXPECT_LT(ahead(frame), 2.0f) << "7 keeps the wall in front, frame " << frame;

  const NamedMotion& toRamp = path.motions()[14];
  EXPECT_GT(ahead(toRamp.first), ahead(toRamp.last) + 3.0f) << "15 moves towards the ramp";
  const Camera last = path.at(toRamp.last);
  const glm::vec2 yawPitch = yawPitchOf(last);
  const Hit ramp = tree.cast(last.position, viewDirection({yawPitch.x, -25.0f}), 10.0f);
  ASSERT_LT(ramp.distance, 10.0f) << "the floor ahead of motion 15's end";
  const float slope = glm::degrees(
      std::acos(std::abs(tree.triangles()[static_cast<size_t>(ramp.triangle)].normal().y)));
  EXPECT_GT(slope, 10.0f) << "degrees: the surface ahead of motion 15's end is a ramp";
  EXPECT_LT(slope, 45.0f);
}

INSTANTIATE_TEST_SUITE_P(OpenArena, StoryboardPaths, ::testing::ValuesIn(plans()), planName);

}  // namespace
}  // namespace vt
