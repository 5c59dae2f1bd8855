#pragma once
// Sub-pixel precision and fill rule from coverage alone (issue 18's "slivers and shared edges at
// known sub-pixel offsets"): probe triangles whose vertices lie at multiples of 2^-12 pixel
// around pixel centres, drawn by the implementation, against every rasterizer of a family that
// snaps vertices to a grid and breaks ties on edges by a fixed rule. The hypotheses every probe
// pixel agrees with are the finding; the coarsest of their grids bounds how far a vertex moves,
// which is what the result sets of an implementation the oracle does not reproduce need
// (reference/result_set_builder.h: corner boxes of 2^-subpixelBits pixel).
//
// Coverage at pixel centres sees where a snapped edge crosses a centre, never the grid between
// centres: b bits rounded to nearest and b + 1 bits truncated cover the same pixels on every
// probe whose vertices lie on the finer grid, so both stay consistent and the coarser grid is
// reported (its 2^-b bounds both displacements).

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/arithmetic.h"
#include "scene/clip_space_mesh.h"

namespace vt::calibrate {

// How a window coordinate X becomes the rasterizer's: 0.5 + round((X - 0.5) * 2^bits) / 2^bits
// (the grid holds the pixel centres).
enum class SnapRounding { kHalfEven, kHalfUp, kFloor, kCeil, kNone };

struct CoverageHypothesis {
  int subpixelBits = 8;  // ignored for kNone (no snapping: the coordinates as drawn)
  SnapRounding rounding = SnapRounding::kHalfEven;
  // A centre exactly on an edge belongs to the triangle when the edge is a left edge (the
  // interior to its right; any edge that is not horizontal is left or right) and leftEdgesIn, or
  // a horizontal bottom edge (the interior above) and bottomEdgesIn. llvmpipe: both
  // (docs/design.md section 7, rule 4).
  bool leftEdgesIn = true;
  bool bottomEdgesIn = true;
  bool operator==(const CoverageHypothesis&) const = default;
};

// In words, e.g. "8 sub-pixel bits, round half to even, centres on left and bottom edges inside".
std::string describe(const CoverageHypothesis& hypothesis);

// The member of the arithmetic's coverage family a hypothesis is (render/arithmetic.h); none for
// unsnapped vertices, which the family draws as float scanline spans instead.
std::optional<Coverage> coverageMember(const CoverageHypothesis& hypothesis);

// Every hypothesis the fit tries: 1 to 14 bits with each rounding, and no snapping, each with the
// four tie rules.
std::vector<CoverageHypothesis> coverageHypotheses();

// A triangle in window coordinates (y up, pixel (px, py) has its centre at (px + 0.5, py + 0.5)),
// drawn alone in the cell of pixels [cellMin, cellMax).
struct CoverageProbe {
  std::array<glm::dvec2, 3> vertices;
  glm::ivec2 cellMin{0, 0}, cellMax{0, 0};
};

// Whether the hypothetical rasterizer covers pixel (px, py) with the probe's triangle.
bool covers(const CoverageHypothesis& hypothesis, const CoverageProbe& probe, int px, int py);

// Probe triangles for a viewport (a fixed seed; the same probes on every run), one per cell of
// 12 x 12 pixels: slivers, small and axis-aligned triangles with vertices at 2^-12 offsets around
// pixel centres, some exactly on them, and edges through centres. Coordinates stay below 1024 so
// that clip-space positions carry them exactly (coverageMesh).
std::vector<CoverageProbe> coverageProbes(unsigned seed, Viewport viewport);

// The probes as clip-space triangles (w = 1, z = 0) for `viewport`, whose width and height must
// be powers of two at most 1024: x_clip = X / (width / 2) - 1 is then exact in float, and so is
// the window coordinate every implementation computes back from it.
ClipSpaceMesh coverageMesh(const std::vector<CoverageProbe>& probes, Viewport viewport);

struct CoverageFit {
  uint64_t pixels = 0;  // the probes' cells, every pixel compared
  // The hypotheses under which every pixel shows what the implementation drew.
  std::vector<CoverageHypothesis> consistent;
  // With none consistent: the hypothesis that disagrees on the fewest pixels, and how many.
  CoverageHypothesis closest;
  uint64_t closestMismatches = 0;
  // The coarsest grid of the consistent hypotheses (no snapping counts as the probes' 12 bits,
  // which no finer grid can be told from); 0 when none is consistent.
  int coarsestBits() const;
};

// The fit to what the implementation drew: `drawn` holds per pixel (row 0 at the bottom) the
// probe's index or -1.
CoverageFit fitCoverage(const std::vector<CoverageProbe>& probes, Viewport viewport,
                        const std::vector<int32_t>& drawn);

}  // namespace vt::calibrate
