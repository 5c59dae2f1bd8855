// The sub-pixel grid fit of `vt calibrate` (calibrate/coverage_fit.h) on coverage it can know:
// readbacks simulated by one rasterizer of the family must be fitted by that rasterizer and give
// its grid, one pixel drawn otherwise must leave no rasterizer consistent, and the probes must
// tell grids, roundings and tie rules apart. The fit on llvmpipe's own readback is checked in
// tests/gl/calibration_test.cpp.

#include "calibrate/coverage_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace vt::calibrate {
namespace {

const Viewport kViewport{256, 128};

// What a rasterizer of the family draws: per pixel the probe's index or -1.
std::vector<int32_t> drawnBy(const CoverageHypothesis& h, const std::vector<CoverageProbe>& probes) {
  std::vector<int32_t> drawn(static_cast<size_t>(kViewport.width * kViewport.height), -1);
  for (size_t k = 0; k < probes.size(); ++k)
    for (int py = probes[k].cellMin.y; py < probes[k].cellMax.y; ++py)
      for (int px = probes[k].cellMin.x; px < probes[k].cellMax.x; ++px)
        if (covers(h, probes[k], px, py))
          drawn[static_cast<size_t>(py * kViewport.width + px)] = static_cast<int32_t>(k);
  return drawn;
}

bool contains(const std::vector<CoverageHypothesis>& list, const CoverageHypothesis& h) {
  return std::find(list.begin(), list.end(), h) != list.end();
}

TEST(CoverageFit, FindsTheGridAndTieRuleThatDrewTheProbes) {
  const std::vector<CoverageProbe> probes = coverageProbes(12, kViewport);
  for (const CoverageHypothesis& truth :
       {CoverageHypothesis{8, SnapRounding::kHalfEven, true, true},
        CoverageHypothesis{4, SnapRounding::kFloor, false, true},
        CoverageHypothesis{6, SnapRounding::kHalfUp, true, false},
        CoverageHypothesis{0, SnapRounding::kNone, false, false}}) {
    const CoverageFit fit = fitCoverage(probes, kViewport, drawnBy(truth, probes));
    EXPECT_TRUE(contains(fit.consistent, truth)) << describe(truth);
    EXPECT_EQ(fit.coarsestBits(), truth.rounding == SnapRounding::kNone ? 12 : truth.subpixelBits)
        << describe(truth);
    // The tie rule is pinned: every consistent rasterizer breaks ties as the one that drew.
    for (const CoverageHypothesis& h : fit.consistent) {
      EXPECT_EQ(h.leftEdgesIn, truth.leftEdgesIn) << describe(truth) << " / " << describe(h);
      EXPECT_EQ(h.bottomEdgesIn, truth.bottomEdgesIn) << describe(truth) << " / " << describe(h);
    }
  }
}

TEST(CoverageFit, OneStrayPixelLeavesNoRasterizerConsistent) {
  const std::vector<CoverageProbe> probes = coverageProbes(12, kViewport);
  const CoverageHypothesis truth{8, SnapRounding::kHalfEven, true, true};
  std::vector<int32_t> drawn = drawnBy(truth, probes);
  // A pixel at the corner of the first cell, far from its triangle, drawn by it.
  const size_t stray = static_cast<size_t>(probes[0].cellMin.y * kViewport.width + probes[0].cellMin.x);
  ASSERT_EQ(drawn[stray], -1);
  drawn[stray] = 0;
  const CoverageFit fit = fitCoverage(probes, kViewport, drawn);
  EXPECT_TRUE(fit.consistent.empty());
  EXPECT_EQ(fit.coarsestBits(), 0);
  EXPECT_EQ(fit.closest, truth);
  EXPECT_EQ(fit.closestMismatches, 1u);
  EXPECT_EQ(fit.pixels, probes.size() * 144u);
}

// The probes separate what they can: no two grids of 1 to 11 bits, and no two tie rules, draw
// them alike (b bits to nearest and b + 1 bits truncated may: pixel centres cannot tell).
TEST(CoverageFit, TheProbesTellGridsAndTieRulesApart) {
  const std::vector<CoverageProbe> probes = coverageProbes(12, kViewport);
  std::set<std::vector<int32_t>> seen;
  int drawings = 0;
  for (const CoverageHypothesis& h : coverageHypotheses()) {
    if (h.rounding != SnapRounding::kHalfEven || h.subpixelBits > 11) continue;
    seen.insert(drawnBy(h, probes));
    ++drawings;
  }
  EXPECT_EQ(static_cast<int>(seen.size()), drawings);
}

TEST(CoverageFit, RefusesAReadbackOfAnotherSizeAndOddViewports) {
  const std::vector<CoverageProbe> probes = coverageProbes(12, kViewport);
  EXPECT_THROW(fitCoverage(probes, kViewport, std::vector<int32_t>(10, -1)), std::invalid_argument);
  EXPECT_THROW(coverageMesh(probes, Viewport{300, 128}), std::invalid_argument);
  // Clip-space positions carry the probes' window coordinates exactly.
  const ClipSpaceMesh mesh = coverageMesh(probes, kViewport);
  ASSERT_EQ(mesh.vertices.size(), 3 * probes.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::dvec2 window = probes[i / 3].vertices[i % 3];
    EXPECT_EQ((static_cast<double>(mesh.vertices[i].position.x) + 1.0) * (kViewport.width / 2),
              window.x);
    EXPECT_EQ((static_cast<double>(mesh.vertices[i].position.y) + 1.0) * (kViewport.height / 2),
              window.y);
  }
}

}  // namespace
}  // namespace vt::calibrate
