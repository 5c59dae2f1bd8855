#include "reference/visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace vt::reference {
namespace {

// What one ray collects while Embree walks the boxes it crosses.
struct PixelQuery {
  RTCIntersectContext context;  // first member: Embree hands its address back to the callbacks
  int px, py;
  DepthFormat format;
  bool fused;
  int32_t best = -1;
  uint32_t bestKey = 0;
  float bestDepth = 1.0f;
  float runnerUpDepth = 1.0f;
};

// The stored depth as an ordered key: Z24 is round-half-even(z * 16777215); 32F is the float,
// whose bits order like its values on [0, 1].
uint32_t depthKey(float z, DepthFormat format) {
  if (format == DepthFormat::kDepth24)
    return static_cast<uint32_t>(std::nearbyint(z * 16777215.0f));
  return std::bit_cast<uint32_t>(z);
}

using SceneView = Visibility::SceneData;

void boundsOf(const RTCBoundsFunctionArguments* args) {
  const auto* data = static_cast<const SceneView*>(args->geometryUserPtr);
  const SetupTriangle& t = (*data->triangles)[args->primID];
  glm::vec3 lo = t.clipXYW[0], hi = t.clipXYW[0];
  for (const glm::vec3& p : t.clipXYW) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const float w = std::max(hi.z, 0.0f);
  const float mx = data->marginPerW[0] * w, my = data->marginPerW[1] * w;
  args->bounds_o->lower_x = lo.x - mx;
  args->bounds_o->lower_y = lo.y - my;
  args->bounds_o->lower_z = lo.z;
  args->bounds_o->upper_x = hi.x + mx;
  args->bounds_o->upper_y = hi.y + my;
  args->bounds_o->upper_z = hi.z;
}

// A candidate: apply the GL rules, keep the winner, never report a hit (so that Embree visits
// every box the ray crosses).
void testCandidate(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* query = reinterpret_cast<PixelQuery*>(args->context);
  const auto* data = static_cast<const SceneView*>(args->geometryUserPtr);
  const int32_t k = static_cast<int32_t>(args->primID);
  const SetupTriangle& t = (*data->triangles)[static_cast<size_t>(k)];
  if (!t.covers(query->px, query->py)) return;
  const float z = windowDepth(t, query->px, query->py, query->fused);
  const uint32_t key = depthKey(z, query->format);
  if (key >= depthKey(1.0f, query->format)) return;  // GL_LESS against the cleared 1.0
  const float stored =
      query->format == DepthFormat::kDepth24 ? static_cast<float>(key) / 16777215.0f : z;
  if (query->best < 0 || key < query->bestKey || (key == query->bestKey && k < query->best)) {
    if (query->best >= 0) query->runnerUpDepth = std::min(query->runnerUpDepth, query->bestDepth);
    query->best = k;
    query->bestKey = key;
    query->bestDepth = stored;
  } else {
    query->runnerUpDepth = std::min(query->runnerUpDepth, stored);
  }
}

void testCandidateOccluded(const RTCOccludedFunctionNArguments*) {}

}  // namespace

float windowDepth(const SetupTriangle& t, int px, int py, bool fused) {
  const float x = static_cast<float>(px), y = static_cast<float>(py);
  const float z = fused ? std::fma(t.z.dady, y, std::fma(t.z.dadx, x, t.z.a0))
                        : t.z.dady * y + (t.z.dadx * x + t.z.a0);
  const float offset = z + 0.0f;  // polygon offset, added even when zero (rule 7)
  return std::clamp(offset, 0.0f, 1.0f);
}

Visibility::Visibility(const std::vector<SetupTriangle>& triangles, Viewport viewport,
                       DepthFormat format, bool fused)
    : data_{&triangles,
            {2.0f / static_cast<float>(viewport.width) / 32.0f,
             2.0f / static_cast<float>(viewport.height) / 32.0f}},
      viewport_(viewport),
      format_(format),
      fused_(fused) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(triangles.size()));
  rtcSetGeometryUserData(geometry, &data_);
  rtcSetGeometryBoundsFunction(geometry, boundsOf, nullptr);
  rtcSetGeometryIntersectFunction(geometry, testCandidate);
  rtcSetGeometryOccludedFunction(geometry, testCandidateOccluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: building the scene failed");
}

Visibility::~Visibility() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

PixelHit Visibility::at(int px, int py) const {
  PixelQuery query;
  rtcInitIntersectContext(&query.context);
  query.px = px;
  query.py = py;
  query.format = format_;
  query.fused = fused_;
  RTCRayHit ray{};
  // The ray of the pixel centre: (x_ndc, y_ndc, 1) in (x, y, w) clip coordinates.
  ray.ray.org_x = ray.ray.org_y = ray.ray.org_z = 0.0f;
  ray.ray.dir_x =
      (static_cast<float>(px) + 0.5f) / (static_cast<float>(viewport_.width) * 0.5f) - 1.0f;
  ray.ray.dir_y =
      (static_cast<float>(py) + 0.5f) / (static_cast<float>(viewport_.height) * 0.5f) - 1.0f;
  ray.ray.dir_z = 1.0f;
  ray.ray.tnear = 0.0f;
  ray.ray.tfar = std::numeric_limits<float>::infinity();
  ray.ray.mask = 0xffffffffu;
  ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &query.context, &ray);
  return {query.best, query.bestDepth, query.runnerUpDepth};
}

}  // namespace vt::reference
