#include "reference/visibility.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace vt::reference {

// What Embree's bounds callback reads: the triangles and the margin of their boxes.
struct BoxData {
  const std::vector<SetupTriangle>* triangles;
  int margin;
};

namespace {

// What one packet collects while Embree walks the boxes its rays cross.
struct BlockQuery {
  RTCIntersectContext context;  // first member: Embree hands its address back to the callbacks
  const std::vector<SetupTriangle>* triangles;
  int x0, y0;
  DepthFormat format;
  const Arithmetic* arithmetic;
  std::array<PixelHit, Visibility::kBlock * Visibility::kBlock> hits;
  std::array<uint32_t, Visibility::kBlock * Visibility::kBlock> keys;
  std::vector<int32_t>* collect = nullptr;  // Visibility::candidates: every box crossed
};

// The stored depth as an ordered key (smaller is nearer), in the depth member
// (render/arithmetic.h). Z24 is round-half-even(z * 16777215) (rule 7) or the C cast (unsigned)(z *
// 16777215.0f) (softpipe-arithmetic.md, 7.1), which on x86-64 truncates through a 64-bit integer
// (NaN gives 0); 32F is the float, whose bits order like its values on [0, 1]. Where z is not
// clamped, 32F is compared as floats: negative depths order below 0, and a NaN never passes
// (kNever).
constexpr uint32_t kNever = 0xffffffffu;
uint32_t depthKey(float z, DepthFormat format, const Depth& depth) {
  if (format == DepthFormat::kDepth24) {
    const float scaled = z * 16777215.0f;
    if (depth.z24 == Z24Conversion::kNearestEven && depth.offsetAndClamp)
      return static_cast<uint32_t>(std::nearbyint(scaled));
    const float whole = depth.z24 == Z24Conversion::kNearestEven ? std::nearbyint(scaled) : scaled;
    const int64_t integer = whole >= -9223372036854775808.0f && whole < 9223372036854775808.0f
                                ? static_cast<int64_t>(whole)
                                : INT64_MIN;
    return static_cast<uint32_t>(static_cast<uint64_t>(integer));
  }
  if (depth.offsetAndClamp) return std::bit_cast<uint32_t>(z);
  if (std::isnan(z)) return kNever;
  const uint32_t bits = std::bit_cast<uint32_t>(z == 0.0f ? 0.0f : z);
  return bits & 0x80000000u ? ~bits : bits | 0x80000000u;
}

void boundsOf(const RTCBoundsFunctionArguments* args) {
  const auto* data = static_cast<const BoxData*>(args->geometryUserPtr);
  const SetupTriangle& t = (*data->triangles)[args->primID];
  // Pixel centres px + 0.5 for px in [minX - margin, maxX + margin], with a quarter pixel to
  // spare each way.
  const float margin = static_cast<float>(data->margin);
  args->bounds_o->lower_x = static_cast<float>(t.minX) + 0.25f - margin;
  args->bounds_o->upper_x = static_cast<float>(t.maxX) + 0.75f + margin;
  args->bounds_o->lower_y = static_cast<float>(t.minY) + 0.25f - margin;
  args->bounds_o->upper_y = static_cast<float>(t.maxY) + 0.75f + margin;
  args->bounds_o->lower_z = 0.0f;
  args->bounds_o->upper_z = 1.0f;
}

// A candidate for some rays of a packet: apply the GL rules per pixel, keep the winner, never
// report a hit (so that Embree visits every box the rays cross).
void testCandidate(const RTCIntersectFunctionNArguments* args) {
  auto* query = reinterpret_cast<BlockQuery*>(args->context);
  const int32_t k = static_cast<int32_t>(args->primID);
  if (query->collect) {
    query->collect->push_back(k);
    return;
  }
  const SetupTriangle& t = (*query->triangles)[static_cast<size_t>(k)];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  for (unsigned lane = 0; lane < args->N; ++lane) {
    if (!args->valid[lane]) continue;
    const int px = static_cast<int>(RTCRayN_org_x(rays, args->N, lane));
    const int py = static_cast<int>(RTCRayN_org_y(rays, args->N, lane));
    if (!t.covers(px, py)) continue;
    const size_t slot =
        static_cast<size_t>((px - query->x0) + Visibility::kBlock * (py - query->y0));
    const float z = windowDepth(t, px, py, *query->arithmetic);
    const Depth& depth = query->arithmetic->depth;
    const uint32_t key = depthKey(z, query->format, depth);
    // GL_LESS against the cleared 1.0
    if (key == kNever || key >= depthKey(1.0f, query->format, depth)) continue;
    const float stored =
        query->format == DepthFormat::kDepth24 ? static_cast<float>(key) / 16777215.0f : z;
    PixelHit& hit = query->hits[slot];
    uint32_t& bestKey = query->keys[slot];
    if (hit.triangle < 0 || key < bestKey || (key == bestKey && k < hit.triangle)) {
      if (hit.triangle >= 0) hit.runnerUpDepth = std::min(hit.runnerUpDepth, hit.depth);
      hit.triangle = k;
      hit.depth = stored;
      bestKey = key;
    } else {
      hit.runnerUpDepth = std::min(hit.runnerUpDepth, stored);
    }
  }
}

void testCandidateOccluded(const RTCOccludedFunctionNArguments*) {}

}  // namespace

float windowDepth(const SetupTriangle& t, int px, int py, const Arithmetic& arithmetic) {
  const float z = evaluatePlane(t.z, px, py, arithmetic.planeEvaluation);
  // No offset term (a polygon offset done as a draw stage, off) and no clamp (depth clamp off):
  // reference/softpipe-arithmetic.md, 7.1.
  if (!arithmetic.depth.offsetAndClamp) return z;
  const float offset = z + 0.0f;  // polygon offset, added even when zero (rule 7)
  return std::clamp(offset, 0.0f, 1.0f);
}

Visibility::Visibility(const std::vector<SetupTriangle>& triangles, Viewport viewport,
                       DepthFormat format, const Arithmetic& arithmetic, int margin)
    : triangles_(triangles),
      viewport_(viewport),
      format_(format),
      arithmetic_(arithmetic),
      margin_(margin) {
  boxData_ = std::make_unique<BoxData>(BoxData{&triangles, margin});
#ifdef VT_STD_THREAD_WORKERS
  // The ThreadSanitizer build (parallel_for.h): Embree's scene build runs on TBB, which TSan
  // cannot follow, so it runs on this thread; the tile workers still trace rays in parallel.
  device_ = rtcNewDevice("threads=1");
#else
  device_ = rtcNewDevice(nullptr);
#endif
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(triangles.size()));
  rtcSetGeometryUserData(geometry, boxData_.get());
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

std::array<PixelHit, Visibility::kBlock * Visibility::kBlock> Visibility::block(int x0,
                                                                                int y0) const {
  BlockQuery query;
  rtcInitIntersectContext(&query.context);
  query.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  query.triangles = &triangles_;
  query.x0 = x0;
  query.y0 = y0;
  query.format = format_;
  query.arithmetic = &arithmetic_;
  query.hits.fill(PixelHit{});
  query.keys.fill(0);
  alignas(64) RTCRayHit16 rays{};
  alignas(64) int valid[16];
  for (int lane = 0; lane < 16; ++lane) {
    const int px = x0 + lane % kBlock, py = y0 + lane / kBlock;
    valid[lane] = px < viewport_.width && py < viewport_.height ? -1 : 0;
    // The ray through the pixel centre, along +z through the boxes' [0, 1].
    rays.ray.org_x[lane] = static_cast<float>(px) + 0.5f;
    rays.ray.org_y[lane] = static_cast<float>(py) + 0.5f;
    rays.ray.org_z[lane] = -1.0f;
    rays.ray.dir_x[lane] = 0.0f;
    rays.ray.dir_y[lane] = 0.0f;
    rays.ray.dir_z[lane] = 1.0f;
    rays.ray.tnear[lane] = 0.0f;
    rays.ray.tfar[lane] = std::numeric_limits<float>::infinity();
    rays.ray.mask[lane] = 0xffffffffu;
    rays.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, scene_, &query.context, &rays);
  return query.hits;
}

void Visibility::candidates(int px, int py, std::vector<int32_t>& out) const {
  out.clear();
  BlockQuery query;
  rtcInitIntersectContext(&query.context);
  query.triangles = &triangles_;
  query.x0 = px;
  query.y0 = py;
  query.format = format_;
  query.arithmetic = &arithmetic_;
  query.collect = &out;
  RTCRayHit ray{};
  ray.ray.org_x = static_cast<float>(px) + 0.5f;
  ray.ray.org_y = static_cast<float>(py) + 0.5f;
  ray.ray.org_z = -1.0f;
  ray.ray.dir_z = 1.0f;
  ray.ray.tnear = 0.0f;
  ray.ray.tfar = std::numeric_limits<float>::infinity();
  ray.ray.mask = 0xffffffffu;
  ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &query.context, &ray);
  std::sort(out.begin(), out.end());
}

PixelHit Visibility::at(int px, int py) const {
  const int x0 = px - px % kBlock, y0 = py - py % kBlock;
  return block(x0, y0)[static_cast<size_t>((px - x0) + kBlock * (py - y0))];
}

}  // namespace vt::reference
