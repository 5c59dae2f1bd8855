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
  // A query of the rays from (x0, y0), for the set-up `triangles`, which it keeps by pointer.
  BlockQuery(const std::vector<SetupTriangle>& triangles, int x0, int y0, DepthFormat format,
             const Arithmetic& arithmetic, int margin)
      : triangles(&triangles),
        x0(x0),
        y0(y0),
        format(format),
        arithmetic(&arithmetic),
        margin(margin) {
    rtcInitIntersectContext(&context);
  }
  RTCIntersectContext context;  // first member: Embree hands its address back to the callbacks
  const std::vector<SetupTriangle>* triangles;
  int x0, y0;
  DepthFormat format;
  const Arithmetic* arithmetic;
  std::array<PixelHit, Visibility::kBlock * Visibility::kBlock> hits{};
  std::array<uint32_t, Visibility::kBlock * Visibility::kBlock> keys{};
  // Visibility::candidates: every triangle whose grown box holds the ray's pixel centre.
  std::vector<int32_t>* collect = nullptr;
  // Visibility::blockCandidates: every triangle whose grown box holds some ray's pixel centre,
  // with those rays (bit dx + 4 dy).
  std::vector<std::pair<int32_t, uint16_t>>* collectBlock = nullptr;
  int margin;
};

// Whether set-up triangle t's box, grown by `margin` and its own candidateMargin (a corner the
// clipper moved), holds the centre of (px, py): Embree calls back for every box of a leaf its
// rays reach, so the candidates keep those whose own box does.
bool boxHolds(const SetupTriangle& t, int margin, int px, int py) {
  margin += t.candidateMargin;
  return t.minX - margin <= px && px <= t.maxX + margin && t.minY - margin <= py &&
         py <= t.maxY + margin;
}

// The stored depth as an ordered key (smaller is nearer), in the depth member
// (render/arithmetic.h). Z24 is round-half-even(z * 16777215) (rule 7) or the C cast (unsigned)(z *
// 16777215.0f) (softpipe-arithmetic.md, 7.1), which on x86-64 truncates through a 64-bit integer
// (NaN gives 0); 32F is the float, whose bits order like its values on [0, 1]. Where z is not
// clamped, 32F is compared as floats: negative depths order below 0, and a NaN never passes
// (kNever).
constexpr uint32_t kNever = 0xffffffffu;
uint32_t depthKey(float z, DepthFormat format, const Depth& depth) {
  if (format == DepthFormat::kDepth24) {
    if (depth.offsetAndClamp) return z24Of(z, depth.z24);  // z is in [0, 1] already
    // Unclamped, as the variant without the viewport clamp stores it: any z, through int64_t.
    const float scaled = z * 16777215.0f;
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
  const float margin = static_cast<float>(data->margin + t.candidateMargin);
  args->bounds_o->lower_x = static_cast<float>(t.minX) + 0.25f - margin;
  args->bounds_o->upper_x = static_cast<float>(t.maxX) + 0.75f + margin;
  args->bounds_o->lower_y = static_cast<float>(t.minY) + 0.25f - margin;
  args->bounds_o->upper_y = static_cast<float>(t.maxY) + 0.75f + margin;
  args->bounds_o->lower_z = 0.0f;
  args->bounds_o->upper_z = 1.0f;
}

// Triangle k (set up as t), which covers pixel (px, py), against the depth test: against the
// clear value and the pixel's winner so far (hit, whose stored key is bestKey), the nearer of the
// two wins, the earlier drawn on a tie. considerCandidate first asks the coverage rule.
inline void considerCovering(const SetupTriangle& t, int32_t k, int px, int py, DepthFormat format,
                             const Arithmetic& arithmetic, PixelHit& hit, uint32_t& bestKey) {
  const float z = windowDepth(t, px, py, arithmetic);
  const Depth& depth = arithmetic.depth;
  const uint32_t key = depthKey(z, format, depth);
  // GL_LESS against the cleared 1.0
  if (key == kNever || key >= depthKey(1.0f, format, depth)) return;
  const float stored = format == DepthFormat::kDepth24 ? static_cast<float>(key) / 16777215.0f : z;
  if (hit.triangle < 0 || key < bestKey || (key == bestKey && k < hit.triangle)) {
    if (hit.triangle >= 0) hit.runnerUpDepth = std::min(hit.runnerUpDepth, hit.depth);
    hit.triangle = k;
    hit.depth = stored;
    bestKey = key;
  } else {
    hit.runnerUpDepth = std::min(hit.runnerUpDepth, stored);
  }
}

inline void considerCandidate(const SetupTriangle& t, int32_t k, int px, int py, DepthFormat format,
                              const Arithmetic& arithmetic, PixelHit& hit, uint32_t& bestKey) {
  if (t.covers(px, py)) considerCovering(t, k, px, py, format, arithmetic, hit, bestKey);
}

// A candidate for some rays of a packet: apply the GL rules per pixel, keep the winner, never
// report a hit (so that Embree visits every box the rays cross).
void testCandidate(const RTCIntersectFunctionNArguments* args) {
  auto* query = reinterpret_cast<BlockQuery*>(args->context);
  const int32_t k = static_cast<int32_t>(args->primID);
  const SetupTriangle& t = (*query->triangles)[static_cast<size_t>(k)];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  if (query->collect || query->collectBlock) {
    uint32_t pixels = 0;
    for (unsigned lane = 0; lane < args->N; ++lane) {
      if (!args->valid[lane]) continue;
      const int px = static_cast<int>(RTCRayN_org_x(rays, args->N, lane));
      const int py = static_cast<int>(RTCRayN_org_y(rays, args->N, lane));
      if (boxHolds(t, query->margin, px, py))
        pixels |= Visibility::BlockCandidates::bitOf(px - query->x0, py - query->y0);
    }
    if (pixels == 0) return;
    if (query->collectBlock)
      query->collectBlock->emplace_back(k, static_cast<uint16_t>(pixels));
    else
      query->collect->push_back(k);
    return;
  }
  for (unsigned lane = 0; lane < args->N; ++lane) {
    if (!args->valid[lane]) continue;
    const int px = static_cast<int>(RTCRayN_org_x(rays, args->N, lane));
    const int py = static_cast<int>(RTCRayN_org_y(rays, args->N, lane));
    const size_t slot =
        static_cast<size_t>((px - query->x0) + Visibility::kBlock * (py - query->y0));
    considerCandidate(t, k, px, py, query->format, *query->arithmetic, query->hits[slot],
                      query->keys[slot]);
  }
}

void testCandidateOccluded(const RTCOccludedFunctionNArguments*) {}

// Traces the 4 x 4 rays of the block at (query.x0, query.y0) as one coherent packet, each along
// +z through its pixel centre and the boxes' [0, 1]; pixels outside the viewport stay inactive.
// The query's callbacks (testCandidate) gather what they are asked for.
void traceBlock(RTCScene scene, Viewport viewport, BlockQuery& query) {
  query.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 rays{};
  alignas(64) int valid[16];
  for (int lane = 0; lane < 16; ++lane) {
    const int px = query.x0 + lane % Visibility::kBlock, py = query.y0 + lane / Visibility::kBlock;
    valid[lane] = px < viewport.width && py < viewport.height ? -1 : 0;
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
  rtcIntersect16(valid, scene, &query.context, &rays);
}

}  // namespace

float windowDepth(const SetupTriangle& t, int px, int py, const Arithmetic& arithmetic) {
  const float z = evaluatePlane(t.z, px, py, arithmetic.planeEvaluation);
  // No offset term (a polygon offset done as a draw stage, off) and no clamp (depth clamp off):
  // reference/softpipe-arithmetic.md, 7.1.
  if (!arithmetic.depth.offsetAndClamp) return z;
  const float offset = z + 0.0f;  // polygon offset, added even when zero (rule 7)
  return std::clamp(offset, 0.0f, 1.0f);
}

namespace {

// The pixels of the viewport that triangle t's box grown by `grow` pixels holds, in 64 bits (a
// clipped corner's candidate margin may be large): [x0, x1] x [y0, y1], empty when x0 > x1.
struct PixelBox {
  int64_t x0, x1, y0, y1;
};
PixelBox grownBox(const SetupTriangle& t, int64_t grow, Viewport viewport) {
  return {std::max<int64_t>(t.minX - grow, 0), std::min<int64_t>(t.maxX + grow, viewport.width - 1),
          std::max<int64_t>(t.minY - grow, 0),
          std::min<int64_t>(t.maxY + grow, viewport.height - 1)};
}

// Bins the triangles into the kTile x kTile tiles their boxes (boxOf) touch, by counting: how many
// each tile holds, then the triangles in draw order; tile i's are binned[start[i] .. start[i + 1]).
template <class BoxOf>
void binByTiles(const std::vector<SetupTriangle>& triangles, Viewport viewport, BoxOf boxOf,
                std::vector<uint32_t>& start, std::vector<uint32_t>& binned) {
  constexpr int kTile = Visibility::kTile;
  const int tilesX = (viewport.width + kTile - 1) / kTile;
  const int tilesY = (viewport.height + kTile - 1) / kTile;
  start.assign(static_cast<size_t>(tilesX) * static_cast<size_t>(tilesY) + 1, 0);
  const auto forEachTile = [&](const SetupTriangle& t, const auto& visit) {
    const PixelBox b = boxOf(t);
    if (b.x0 > b.x1 || b.y0 > b.y1) return;
    for (int64_t ty = b.y0 / kTile; ty <= b.y1 / kTile; ++ty)
      for (int64_t tx = b.x0 / kTile; tx <= b.x1 / kTile; ++tx)
        visit(static_cast<size_t>(ty) * static_cast<size_t>(tilesX) + static_cast<size_t>(tx));
  };
  for (const SetupTriangle& t : triangles) forEachTile(t, [&](size_t i) { ++start[i + 1]; });
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  binned.resize(start.back());
  std::vector<uint32_t> next(start.begin(), start.end() - 1);
  for (size_t k = 0; k < triangles.size(); ++k)
    forEachTile(triangles[k], [&](size_t i) { binned[next[i]++] = static_cast<uint32_t>(k); });
}

}  // namespace

Visibility::Visibility(const std::vector<SetupTriangle>& triangles, Viewport viewport,
                       DepthFormat format, const Arithmetic& arithmetic, int margin,
                       CandidateSearch search)
    : triangles_(triangles),
      viewport_(viewport),
      format_(format),
      arithmetic_(arithmetic),
      margin_(margin),
      search_(search) {
  boxData_ = std::make_unique<BoxData>(BoxData{&triangles, margin});
  tilesX_ = (viewport.width + kTile - 1) / kTile;
  // The tile rasterizer's bins: each triangle's own box of candidate centres.
  binByTiles(
      triangles, viewport, [&](const SetupTriangle& t) { return grownBox(t, 0, viewport); },
      binStart_, binned_);
}

void Visibility::buildScene() const {
  std::call_once(built_, [this] {
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
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(triangles_.size()));
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
  });
}

Visibility::~Visibility() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void Visibility::tile(int x0, int y0, std::span<PixelHit, kTile * kTile> hits) const {
  std::fill(hits.begin(), hits.end(), PixelHit{});
  std::array<uint32_t, kTile * kTile> keys{};
  const size_t bin = static_cast<size_t>(y0 / kTile) * static_cast<size_t>(tilesX_) +
                     static_cast<size_t>(x0 / kTile);
  const int xEnd = std::min(x0 + kTile, viewport_.width) - 1,
            yEnd = std::min(y0 + kTile, viewport_.height) - 1;
  for (uint32_t i = binStart_[bin]; i < binStart_[bin + 1]; ++i) {
    const int32_t k = static_cast<int32_t>(binned_[i]);
    const SetupTriangle& t = triangles_[static_cast<size_t>(k)];
    for (int py = std::max(t.minY, y0); py <= std::min(t.maxY, yEnd); ++py) {
      const auto [first, last] = t.coveredSpan(py, std::max(t.minX, x0), std::min(t.maxX, xEnd));
      for (int px = first; px <= last; ++px) {
        const size_t slot = static_cast<size_t>((px - x0) + kTile * (py - y0));
        considerCovering(t, k, px, py, format_, arithmetic_, hits[slot], keys[slot]);
      }
    }
  }
}

std::array<PixelHit, Visibility::kBlock * Visibility::kBlock> Visibility::block(int x0,
                                                                                int y0) const {
  buildScene();
  BlockQuery query(triangles_, x0, y0, format_, arithmetic_, margin_);
  traceBlock(scene_, viewport_, query);
  return query.hits;
}

void Visibility::candidates(int px, int py, std::vector<int32_t>& out) const {
  out.clear();
  buildScene();
  BlockQuery query(triangles_, px, py, format_, arithmetic_, margin_);
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

void Visibility::BlockCandidates::of(int dx, int dy, std::vector<int32_t>& out) const {
  out.clear();
  const uint16_t bit = bitOf(dx, dy);
  for (size_t i = 0; i < triangles.size(); ++i)
    if (pixels[i] & bit) out.push_back(triangles[i]);
}

namespace {

// Triangle t's box grown by `margin` and its own candidateMargin, in the viewport.
PixelBox candidateBox(const SetupTriangle& t, int margin, Viewport viewport) {
  return grownBox(t, int64_t{margin} + t.candidateMargin, viewport);
}

}  // namespace

void Visibility::binCandidates() const {
  std::call_once(candidatesBinned_, [this] {
    binByTiles(
        triangles_, viewport_,
        [&](const SetupTriangle& t) { return candidateBox(t, margin_, viewport_); },
        candidateStart_, candidateBinned_);
  });
}

void Visibility::blockCandidatesFromBins(int x0, int y0, BlockCandidates& out) const {
  binCandidates();
  const size_t bin = static_cast<size_t>(y0 / kTile) * static_cast<size_t>(tilesX_) +
                     static_cast<size_t>(x0 / kTile);
  for (uint32_t i = candidateStart_[bin]; i < candidateStart_[bin + 1]; ++i) {
    const int32_t k = static_cast<int32_t>(candidateBinned_[i]);
    const PixelBox b = candidateBox(triangles_[static_cast<size_t>(k)], margin_, viewport_);
    // The block's columns and rows inside the box (and so inside the viewport).
    const int64_t c0 = std::max<int64_t>(b.x0 - x0, 0),
                  c1 = std::min<int64_t>(b.x1 - x0, kBlock - 1);
    const int64_t r0 = std::max<int64_t>(b.y0 - y0, 0),
                  r1 = std::min<int64_t>(b.y1 - y0, kBlock - 1);
    if (c0 > c1 || r0 > r1) continue;
    const unsigned row = ((1u << (c1 + 1)) - 1u) & ~((1u << c0) - 1u);
    unsigned pixels = 0;
    for (int64_t r = r0; r <= r1; ++r) pixels |= row << (kBlock * r);
    out.triangles.push_back(k);
    out.pixels.push_back(static_cast<uint16_t>(pixels));
  }
}

void Visibility::blockCandidates(int x0, int y0, BlockCandidates& out) const {
  out.triangles.clear();
  out.pixels.clear();
  if (search_ == CandidateSearch::kBins) {
    blockCandidatesFromBins(x0, y0, out);
    return;
  }
  buildScene();
  BlockQuery query(triangles_, x0, y0, format_, arithmetic_, margin_);
  thread_local std::vector<std::pair<int32_t, uint16_t>> reports;
  reports.clear();
  query.collectBlock = &reports;
  traceBlock(scene_, viewport_, query);
  // Draw order; a triangle Embree reported more than once keeps the union of its pixels.
  std::sort(reports.begin(), reports.end());
  for (const auto& [triangle, pixels] : reports) {
    if (!out.triangles.empty() && out.triangles.back() == triangle) {
      out.pixels.back() = static_cast<uint16_t>(out.pixels.back() | pixels);
      continue;
    }
    out.triangles.push_back(triangle);
    out.pixels.push_back(pixels);
  }
}

PixelHit Visibility::at(int px, int py) const {
  const int x0 = px - px % kBlock, y0 = py - py % kBlock;
  return block(x0, y0)[static_cast<size_t>((px - x0) + kBlock * (py - y0))];
}

uint32_t z24Of(float z, Z24Conversion conversion) {
  const float scaled = (z > 0.0f ? std::min(z, 1.0f) : 0.0f) * 16777215.0f;  // NaN gives 0
  return static_cast<uint32_t>(conversion == Z24Conversion::kNearestEven ? std::nearbyint(scaled)
                                                                         : scaled);
}

}  // namespace vt::reference
