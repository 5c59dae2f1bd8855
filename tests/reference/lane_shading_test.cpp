// The oracle's two ways of drawing a frame give the same bytes: eight pixels per SIMD call
// (reference/lane_shading.h) and one at a time (RenderSettings::scalarShading), for every named
// arithmetic, both texture views, every shader switch and extreme texture coordinates; and its
// two visibility searches agree: tiles walked by the binned rasterizer and Embree's packets.

#include "reference/lane_shading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "build/synthetic_texture.h"
#include "reference/random_triangles.h"
#include "reference/renderer.h"
#include "reference/shader_math.h"
#include "reference/visibility.h"
#include "render/arithmetic_points.h"
#include "render/cache_state.h"
#include "shader/lanes.h"
#include "test_support.h"

namespace vt::reference {
namespace {

// A tilted, perspective height field of 24 x 24 cells over most of the viewport (beyond it at
// the top and bottom, short of it at the sides), plus
// triangles whose texture coordinates are extreme: NaN, infinite, far outside [0, 1], and a
// sliver minified to one texel per screen.
ClipSpaceMesh scene() {
  ClipSpaceMesh mesh;
  constexpr int kCells = 24;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const float x = -0.9f + 1.8f * static_cast<float>(i) / kCells;
      const float y = -1.2f + 2.4f * static_cast<float>(j) / kCells;
      const float w = 1.0f + 0.6f * (y + 1.2f) + 0.05f * std::sin(7.0f * x);
      mesh.vertices.push_back({{x * w, y * w, (0.3f * y + 0.1f * std::cos(5.0f * x)) * w, w},
                               {0.5f + 0.45f * x * std::abs(x), 0.5f + 0.4f * y}});
    }
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (kCells + 1) + i), b = a + 1, c = a + kCells + 1,
                     d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
    }
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const auto triangle = [&](glm::vec2 centre, float size, glm::vec2 uv0, glm::vec2 uv1,
                            glm::vec2 uv2) {
    const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back({{centre.x - size, centre.y - size, -0.5f, 1.0f}, uv0});
    mesh.vertices.push_back({{centre.x + size, centre.y - size, -0.5f, 1.0f}, uv1});
    mesh.vertices.push_back({{centre.x, centre.y + size, -0.5f, 1.0f}, uv2});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
  };
  triangle({-0.6f, 0.5f}, 0.15f, {nan, 0.2f}, {0.3f, nan}, {0.5f, 0.5f});
  triangle({0.0f, 0.5f}, 0.15f, {inf, 0.2f}, {-inf, 0.3f}, {0.5f, 1e30f});
  triangle({0.6f, 0.5f}, 0.15f, {-3.0f, 7.0f}, {12.0f, -5.0f}, {1.0f, 1.0f});
  triangle({-0.6f, -0.5f}, 0.2f, {0.25f, 0.25f}, {0.25f + 1e-7f, 0.25f}, {0.25f, 0.25f + 1e-7f});
  triangle({0.6f, -0.5f}, 0.02f, {0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f});
  return mesh;
}

class LaneShading : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (!lanes::lanesAvailable()) GTEST_SKIP() << "this CPU has no AVX2: only scalar shading";
  }

  // Draws `mesh` both ways with `settings` and the point's arithmetic, and compares every
  // channel.
  template <class Texture>
  void expectSameBytes(const Texture& texture, RenderSettings settings, const std::string& what) {
    settings.arithmetic = arithmeticPoint(GetParam());
    settings.viewport = {157, 93};  // tiles, blocks and quads cut at the right and top edges
    settings.debugChannels = true;
    settings.threads = 2;
    settings.scalarShading = true;
    const Frame scalar = renderFrame(mesh_, texture, settings);
    settings.scalarShading = false;
    const Frame lanes = renderFrame(mesh_, texture, settings);
    EXPECT_EQ(lanes.color, scalar.color) << what;
    EXPECT_EQ(lanes.need, scalar.need) << what;
    EXPECT_EQ(lanes.depth, scalar.depth) << what;
    EXPECT_EQ(lanes.triangle, scalar.triangle) << what;
    EXPECT_EQ(lanes.lod.size(), scalar.lod.size()) << what;
    for (size_t i = 0; i < lanes.lod.size(); ++i) {
      // Bits, so that NaN compares equal to NaN and -0 differs from +0.
      ASSERT_EQ(std::bit_cast<uint32_t>(lanes.lod[i]), std::bit_cast<uint32_t>(scalar.lod[i]))
          << what << ", pixel " << i;
      ASSERT_EQ(lanes.residentLevel[i], scalar.residentLevel[i]) << what << ", pixel " << i;
    }
    EXPECT_GT(std::count(scalar.triangle.begin(), scalar.triangle.end(), -1), 0) << what;
  }

  const ClipSpaceMesh mesh_ = scene();
  test::ScratchDirectory dir_;
};

INSTANTIATE_TEST_SUITE_P(NamedPoints, LaneShading, ::testing::ValuesIn(arithmeticPointNames()),
                         [](const auto& info) { return info.param; });

// Every combination of the shader's switches that changes what a lane computes.
std::vector<std::pair<std::string, RenderSettings>> switches() {
  std::vector<std::pair<std::string, RenderSettings>> all;
  for (const bool trilinear : {true, false})
    for (const bool exactFilter : {true, false}) {
      RenderSettings s;
      s.trilinear = trilinear;
      s.exactFilter = exactFilter;
      all.emplace_back(std::string(trilinear ? "trilinear" : "bilinear") +
                           (exactFilter ? " texel fetches" : " GL_LINEAR"),
                       s);
    }
  RenderSettings need8;
  need8.need8 = true;
  need8.depthFormat = DepthFormat::kDepth24;
  all.emplace_back("8-bit needbuffer, Z24", need8);
  RenderSettings needOnly;
  needOnly.needOnly = true;
  needOnly.needScaleLog2 = 2;
  all.emplace_back("needbuffer only, need scale 2", needOnly);
  return all;
}

TEST_P(LaneShading, EveryPageResidentGivesTheSameBytesAsOnePixelAtATime) {
  // Three channels: the resident view expands each texel to RGBA lane by lane.
  for (const uint32_t channels : {4u, 3u}) {
    const auto file = dir_ / ("t" + std::to_string(channels) + ".vt");
    writeSyntheticTexture(
        file, {{.pageSize = 16, .border = 2, .levelCount = 6, .channels = channels}, std::nullopt});
    const VirtualTextureReader reader(file);
    const ResidentTexture texture(reader);
    for (const auto& [what, settings] : switches())
      expectSameBytes(texture, settings, what + ", " + std::to_string(channels) + " channels");
  }
}

// Measured tables (render/measured_table.h) for the reciprocal and sqrt, far from IEEE (every
// reciprocal 4 ulps low, every square root 2^-7 high): lane by lane they shade what one pixel at
// a time does, and the frame is not the IEEE one, so both paths take them.
TEST_P(LaneShading, MeasuredTablesShadeTheSameBytesAsOnePixelAtATime) {
  writeSyntheticTexture(
      dir_ / "t.vt", {{.pageSize = 16, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(dir_ / "t.vt");
  const ResidentTexture texture(reader);
  std::vector<uint32_t> reciprocal(MeasuredTable::kReciprocalCount);
  std::vector<uint32_t> root(MeasuredTable::kSqrtCount);
  for (uint32_t i = 0; i < reciprocal.size(); ++i) {
    const float r = 1.0f / std::bit_cast<float>(0x3f800000u + i);
    reciprocal[i] = std::max(std::bit_cast<uint32_t>(0.5f), std::bit_cast<uint32_t>(r) - 4);
  }
  for (uint32_t i = 0; i < root.size(); ++i) {
    const float s = std::sqrt(std::bit_cast<float>(0x3f800000u + i)) * (1.0f + 0x1p-7f);
    root[i] = std::bit_cast<uint32_t>(std::min(2.0f, s));
  }
  RenderSettings settings;
  settings.arithmetic = arithmeticPoint(GetParam());
  settings.viewport = {157, 93};
  settings.debugChannels = true;
  settings.threads = 2;
  const Frame ieee = renderFrame(mesh_, texture, settings);
  settings.arithmetic.perspective = Perspective::kReciprocalTimes;
  settings.arithmetic.reciprocal.table =
      std::make_shared<const MeasuredTable>(TabledFunction::kReciprocal, reciprocal);
  settings.arithmetic.sqrt.table =
      std::make_shared<const MeasuredTable>(TabledFunction::kSqrt, root);
  settings.scalarShading = true;
  const Frame scalar = renderFrame(mesh_, texture, settings);
  settings.scalarShading = false;
  const Frame lanes = renderFrame(mesh_, texture, settings);
  EXPECT_EQ(lanes.color, scalar.color);
  EXPECT_EQ(lanes.need, scalar.need);
  // Bits, so that NaN (the mesh has NaN coordinates) compares equal to NaN.
  const auto sameBytes = [](const auto& a, const auto& b) {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(a.front())) == 0;
  };
  EXPECT_TRUE(sameBytes(lanes.uv, scalar.uv));
  EXPECT_TRUE(sameBytes(lanes.lod, scalar.lod));
  EXPECT_FALSE(sameBytes(scalar.uv, ieee.uv));
  EXPECT_FALSE(sameBytes(scalar.lod, ieee.lod));
}

TEST_P(LaneShading, ACacheStateWithMissingPagesGivesTheSameBytesAsOnePixelAtATime) {
  // Every third stored page resident: many lookups fall back to an ancestor, and neighbouring
  // lanes read different pages of different levels.
  writeSyntheticTexture(
      dir_ / "t.vt", {{.pageSize = 16, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const VirtualTextureReader reader(dir_ / "t.vt");
  std::vector<uint64_t> pages;
  for (uint64_t p = 0; p < reader.storedPageCount(); p += 3) pages.push_back(p);
  const CacheState cache = makeCacheState(reader, pages, 40, 40);
  for (const auto& [what, settings] : switches()) expectSameBytes(cache, settings, what);
}

TEST(LanePolynomialLog2, EveryLaneGivesTheScalarFunctionsBits) {
  if (!lanes::lanesAvailable()) GTEST_SKIP() << "this CPU has no AVX2";
  // Special values (zeros, denormals, infinities, NaNs, negatives, powers of two and their
  // neighbours) and random bit patterns of every exponent, under both denormal modes.
  std::vector<uint32_t> bits = {0x00000000u, 0x80000000u, 0x00000001u, 0x007fffffu, 0x00800000u,
                                0x3f800000u, 0x3f7fffffu, 0x3f800001u, 0x7f7fffffu, 0x7f800000u,
                                0xff800000u, 0x7fc00000u, 0x7f800001u, 0xbf800000u, 0x80000001u,
                                0x40000000u, 0x3f000000u};
  std::mt19937 random(17);
  for (int k = 0; k < 20000; ++k) bits.push_back(static_cast<uint32_t>(random()));
  while (bits.size() % 8 != 0) bits.push_back(0x3f800000u);
  for (const bool flush : {false, true}) {
    const DenormalMode mode(flush);
    for (const bool fused : {false, true})
      for (size_t i = 0; i < bits.size(); i += 8) {
        float in[8], out[8];
        for (size_t k = 0; k < 8; ++k) in[k] = std::bit_cast<float>(bits[i + k]);
        polynomialLog2EightAtOnce(in, out, fused);
        for (size_t k = 0; k < 8; ++k)
          ASSERT_EQ(std::bit_cast<uint32_t>(out[k]),
                    std::bit_cast<uint32_t>(polynomialLog2(in[k], fused)))
              << std::hex << bits[i + k] << (fused ? " fused" : " unfused")
              << (flush ? ", flushing denormals" : "");
      }
  }
}

TEST_P(LaneShading, AQuadPairsAttributesInLanesAreAttributesAtPixelByPixel) {
  // Planes of random magnitudes (steep, flat, near zero, denormal, huge, zero 1/w) at quad pairs
  // anywhere in a 16384-pixel viewport, under both denormal modes: every lane the bits of the
  // one-pixel function at its pixel, helpers included.
  const Arithmetic arithmetic = arithmeticPoint(GetParam());
  std::mt19937 random(23);
  std::uniform_real_distribution<float> mantissa(-2.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(-140, 40), position(0, 8191);
  const auto value = [&] {  // the exponent drawn first (one statement each: see common/random_draws.h)
    const int e = exponent(random);
    return std::ldexp(mantissa(random), e);
  };
  const auto plane = [&] { return Plane{value(), value(), value()}; };
  for (const bool flush : {false, true}) {
    const DenormalMode mode(flush);
    for (int k = 0; k < 4000; ++k) {
      SetupTriangle t;
      t.oneOverW = k % 97 == 0 ? Plane{} : plane();
      t.s = plane();
      t.t = plane();
      const int qx = 2 * position(random), qy = 2 * position(random);
      float u[lanes::kLanes], v[lanes::kLanes];
      quadPairAttributes(t, qx, qy, arithmetic, u, v);
      for (int lane = 0; lane < lanes::kLanes; ++lane) {
        const int px = qx + 2 * (lane >> 2) + (lane & 1), py = qy + ((lane >> 1) & 1);
        const glm::vec2 expected = attributesAt(t, px, py, arithmetic).uv;
        ASSERT_EQ(std::bit_cast<uint32_t>(u[lane]), std::bit_cast<uint32_t>(expected.x))
            << "lane " << lane << ", plane " << k << (flush ? ", flushing denormals" : "");
        ASSERT_EQ(std::bit_cast<uint32_t>(v[lane]), std::bit_cast<uint32_t>(expected.y))
            << "lane " << lane << ", plane " << k << (flush ? ", flushing denormals" : "");
      }
    }
  }
}

TEST_P(LaneShading, TheTileRasterizerAgreesWithEmbreesPacketsOnEveryPixel) {
  // Random overlapping triangles, two coplanar copies of one (the earlier drawn wins), both depth
  // formats: the winner, its stored depth and the runner-up's must be the same bits.
  const ClipSpaceMesh mesh = test::randomTrianglesWithCoplanarCopies(150, 11);
  const Arithmetic arithmetic = arithmeticPoint(GetParam());
  const Viewport viewport{101, 67};
  const auto triangles = setupTriangles(mesh, viewport, arithmetic);
  // The rasterizer walks each row's covered span, solved per edge: exactly the pixels covers()
  // accepts, including rows cut short by the window given.
  size_t spans = 0;
  for (const SetupTriangle& t : triangles)
    for (int py = t.minY; py <= t.maxY; ++py)
      for (const auto& [lo, hi] : {std::pair{t.minX, t.maxX}, std::pair{t.minX + 3, t.maxX - 2}}) {
        const auto [first, last] = t.coveredSpan(py, lo, hi);
        for (int px = lo; px <= hi; ++px)
          ASSERT_EQ(px >= first && px <= last, t.covers(px, py)) << px << ", " << py;
        spans += first <= last;
      }
  EXPECT_GT(spans, 1000u);
  for (const DepthFormat format : {DepthFormat::kDepth32F, DepthFormat::kDepth24}) {
    const Visibility visibility(triangles, viewport, format, arithmetic);
    std::array<PixelHit, Visibility::kTile * Visibility::kTile> tile;
    size_t covered = 0;
    for (int y0 = 0; y0 < viewport.height; y0 += Visibility::kTile)
      for (int x0 = 0; x0 < viewport.width; x0 += Visibility::kTile) {
        visibility.tile(x0, y0, tile);
        for (int by = y0; by < y0 + Visibility::kTile; by += Visibility::kBlock)
          for (int bx = x0; bx < x0 + Visibility::kTile; bx += Visibility::kBlock) {
            const auto block = visibility.block(bx, by);
            for (int k = 0; k < Visibility::kBlock * Visibility::kBlock; ++k) {
              const int px = bx + k % Visibility::kBlock, py = by + k / Visibility::kBlock;
              const PixelHit& a =
                  tile[static_cast<size_t>((px - x0) + Visibility::kTile * (py - y0))];
              const PixelHit& b = block[static_cast<size_t>(k)];
              ASSERT_EQ(a.triangle, b.triangle) << px << ", " << py;
              ASSERT_EQ(std::bit_cast<uint32_t>(a.depth), std::bit_cast<uint32_t>(b.depth));
              ASSERT_EQ(std::bit_cast<uint32_t>(a.runnerUpDepth),
                        std::bit_cast<uint32_t>(b.runnerUpDepth));
              covered += a.triangle >= 0;
            }
          }
      }
    EXPECT_GT(covered, static_cast<size_t>(viewport.width * viewport.height / 2));
  }
}

}  // namespace
}  // namespace vt::reference
