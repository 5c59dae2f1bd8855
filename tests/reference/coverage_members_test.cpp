// The oracle draws every member of the coverage family (render/arithmetic.h) as the calibration's
// coverage fit defines it (calibrate/coverage_fit.h): for each snapping grid, rounding and tie
// rule, the set-up triangles' edge functions cover exactly the pixels `covers` says, on probe
// triangles with vertices at 2^-12 offsets around pixel centres, on them and on edges through
// them. So a grid and tie rule the calibration pins is one the oracle reproduces.

#include <gtest/gtest.h>

#include "calibrate/coverage_fit.h"
#include "reference/triangle_setup.h"
#include "render/arithmetic_points.h"

namespace vt::reference {
namespace {

TEST(CoverageMembers, TheOracleCoversAsEveryHypothesisOfTheFitSays) {
  const Viewport viewport{256, 128};
  const std::vector<calibrate::CoverageProbe> probes = calibrate::coverageProbes(5, viewport);
  const ClipSpaceMesh mesh = calibrate::coverageMesh(probes, viewport);
  int members = 0;
  for (const calibrate::CoverageHypothesis& h : calibrate::coverageHypotheses()) {
    const std::optional<Coverage> member = calibrate::coverageMember(h);
    if (!member) continue;  // unsnapped: drawn as spans, not by edge functions
    Arithmetic arithmetic = arithmeticPoint("exact");
    arithmetic.coverage = *member;
    const std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, arithmetic);
    std::vector<std::vector<const SetupTriangle*>> byProbe(probes.size());
    for (const SetupTriangle& t : triangles) byProbe.at(t.primitive).push_back(&t);
    uint64_t differ = 0, covered = 0;
    for (size_t p = 0; p < probes.size(); ++p) {
      const calibrate::CoverageProbe& probe = probes[p];
      for (int py = probe.cellMin.y; py < probe.cellMax.y; ++py)
        for (int px = probe.cellMin.x; px < probe.cellMax.x; ++px) {
          bool oracle = false;
          for (const SetupTriangle* t : byProbe[p])
            oracle = oracle || (px >= t->minX && px <= t->maxX && py >= t->minY && py <= t->maxY &&
                                t->covers(px, py));
          const bool fit = calibrate::covers(h, probe, px, py);
          differ += oracle != fit;
          covered += fit;
        }
    }
    EXPECT_EQ(differ, 0u) << calibrate::describe(h);
    EXPECT_GT(covered, 0u) << calibrate::describe(h);
    ++members;
  }
  EXPECT_EQ(members, 14 * 4 * 4);
}

}  // namespace
}  // namespace vt::reference
