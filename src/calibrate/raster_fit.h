#pragma once
// The rasterization families of the arithmetic (render/arithmetic.h) fitted from probe draws:
// coverage, the viewport transform, the plane setup and evaluation, perspective and depth.
//
// Coverage alone first (coverage_fit.h: 3,570 triangles at 2^-12 offsets around pixel centres
// against 228 snapping rasterizers): its consistent members, and float scanline spans, are the
// coverage candidates. Then 360 random triangles (slivers, perspective, near-plane clipping, a
// coplanar pair) and 60 whose clipped remains lie at window z 0 up to rounding, drawn into 32F
// depth, whose triangle, texture coordinates, fine derivatives and
// depth are compared bit for bit with the oracle drawing them in every combination of the
// candidates and the members of the other families (viewport 2, plane setup 2, plane evaluation
// 3, perspective 2, depth offset and clamp 2). A family is pinned when every combination that
// reproduces every probe has the same member; when combinations with different members all do,
// the probes cannot tell them apart, and the first is taken and said so. The Z24 conversion is
// fitted last, from 120 more triangles drawn into Z24 under the chosen members. Where the folder
// holds the plane group (plane_probes.h), its triangles join the combinations, the shifted
// copies' evidence goes into plane_evaluation's finding, and its constant-depth squares fit the
// Z24 conversion whether or not the rest is reproduced.
//
// When no combination reproduces everything, the closest one (fewest pixels of another
// triangle, then of other attributes, then of other depth) is taken, and the attributes and depth
// are bounded by their residuals in the precision model's units (render/precision_model.h),
// measured against the oracle's result sets under the model with those two bounds at 0: what
// vertices moved within the sub-pixel grid explain is not counted twice.

#include "calibrate/family_fit.h"
#include "probes/probe_draws.h"
#include "render/arithmetic.h"
#include "render/frame.h"
#include "render/precision_model.h"

namespace vt::reference {
class ResidentTexture;
}

namespace vt::calibrate {

// What an arithmetic's frame misses of an implementation's readbacks of the same probes: pixels
// showing another triangle, pixels of the same triangle whose texture coordinates or fine
// derivatives differ in a bit, and those whose depth does.
struct RasterCounts {
  uint64_t pixels = 0, coverage = 0, shared = 0, attributes = 0, depth = 0;
  uint64_t differing = 0;  // pixels that differ in any of coverage, attributes and depth
  // Over the pixels of the same triangle, the floats between the oracle's values and the
  // implementation's, each capped at kDistanceCap: (s, t) and the four derivatives, and depth.
  // Where no combination reproduces a GPU, nearly every pixel differs in some bit under every
  // member; how far they differ tells the members apart.
  double attributeDistance = 0, depthDistance = 0;
  static constexpr double kDistanceCap = 0x1p16;
  bool reproduces() const { return differing == 0; }
  uint64_t total() const { return differing; }
};
// Adds what `oracle` (drawn with debug channels) misses of `gl` to `counts`.
void compareRaster(const RasterReadback& gl, const Frame& oracle, RasterCounts& counts);

// The oracle's frame of a probe mesh, with debug channels (triangle, coordinates, derivatives).
Frame oracleFrame(const ClipSpaceMesh& mesh, const reference::ResidentTexture& texture,
                  Viewport viewport, const Arithmetic& arithmetic, DepthFormat format);

struct RasterFits {
  std::vector<ParameterFit> fits;  // coverage, subpixel_bits, viewport, plane_setup,
                                   // plane_evaluation, perspective, depth_offset, z24
  ParameterFit attributes, depth;  // the residuals of the combination taken
  Arithmetic arithmetic;           // the members taken (the rest of `base` unchanged)
  bool coveragePinned = false;     // coverage reproduced bit for bit
  int subpixelBits = 0;            // the coarsest grid coverage alone allows; 0: none fits
  double attributeUlps = 0, depthUlps = 0;
  uint64_t unexplainedOwners = 0;  // pixels whose triangle the bounded model's sets do not admit
  bool depthBeyondSets = false;    // not even gl45's depth bound admits them all
  bool z24Pinned = false;
};

// The member `a` has of a rasterization family, by the family's name in the evidence
// ("coverage", "viewport", "plane_setup", "plane_positions", "plane_evaluation", "perspective",
// "depth_offset", "z24"); empty for another name.
std::string rasterMemberOf(const std::string& family, const Arithmetic& a);
// A coverage member's name in the evidence, e.g. "8_bits_half_even_left_bottom".
std::string nameOf(const Coverage& coverage);

// Coverage in a model whose arithmetic is set: the arithmetic's own where its coverage was
// reproduced (`coveragePinned`), else ties free on the coarsest grid coverage alone allows
// (`gridBits`, 0: none, gl45's stays).
void setCoverageBounds(PrecisionModel& model, bool coveragePinned, int gridBits);

// Draws the probes on the current GL context. `base`: the shader members already fitted (log2,
// denormals, ...), which the oracle draws with.
RasterFits fitRasterization(const Arithmetic& base);

}  // namespace vt::calibrate
