#pragma once
// The builder of pixels' result sets (result_set_builder.h) and what it keeps between pixels: the
// candidates' moved corners, the classes of a block's candidates, the oracle's own triangle over a
// block, the last cells read. Its parts, by job:
//   set_coverage.cpp   moved corners, coverage and depth (which triangle may own a pixel);
//   set_fragment.cpp   (s, t), fine derivatives and LOD of a candidate, and its alternative;
//   set_own_block.cpp  the oracle's own triangle over a block: shared widths and kept texels;
//   set_filter.cpp     the colour: levels, pages, the bilinear filter's bounds and the 8-bit store.

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "reference/result_set_builder.h"
#include "reference/set_parts.h"

namespace vt::reference::sets {

class Builder {
 public:
  Builder(const PrecisionModel& model, const SetShading& shading, Viewport viewport,
          TexelSource& source)
      : model_(model), shading_(shading), viewport_(viewport), source_(source) {
    finestSide_ = std::ldexp(
        static_cast<double>(shading.pageSize) * static_cast<double>(1 << shading.finestLevel),
        -shading.needScaleLog2);
    subTexelStep_ = std::ldexp(1.0, -model.subTexelBits);
    if (const Filter& f = model.arithmetic.filter; !shading.exactFilter && model.filterPinned &&
                                                   f.weights == FilterWeights::kFixedPointCorners)
      cornerStep_ = std::ldexp(f.lerpRounding == LerpRounding::kNearest ? 0.5 : 1.0, -f.weightBits);
  }

  // Whether the model lets vertices move at all (else coverage, depth and attributes are the
  // oracle's own values and nothing needs a Snapped).
  bool movesVertices() const {
    return !model_.coveragePinned() || model_.depthUlps != 0 || !model_.depthRoundsToNearest ||
           model_.attributeUlps != 0;
  }

  // Candidate `index`'s moved corners, made once per builder (a tile's pixels share them); null
  // when the model moves no vertex.
  Snapped* snapped(const SetupTriangle& t, int32_t index);

  // The classes over the block from (bx, by) of its candidates (`count` of them), by their
  // position in its list, each made by the first pixel that asks (cover unknown before). The
  // blocks of a quad row of a tile are visited in turns, so one slot per block column is kept.
  std::vector<BlockClass>& blockClasses(int bx, int by, size_t count);

  // Candidate `index`'s class over the block from (bx, by); its pixels decide alone (cover -1, any
  // depth) under pinned coverage and for triangles too small for first-order bounds.
  BlockClass blockClass(const SetupTriangle& t, int32_t index, int bx, int by, DepthFormat format);

  // Coverage of candidate t at the centre of (px, py); `s` is needed unless coverage is pinned.
  PieceCoverage coverage(const SetupTriangle& t, Snapped* s, int px, int py) const;

  // Window depth of candidate t at (px, py) as the depth test compares it.
  Interval depth(const SetupTriangle& t, Snapped* s, int px, int py, DepthFormat format) const;

  FragmentRange fragment(const SetupTriangle& t, Snapped* snapped, int px, int py) const;

  // The needed level's bounds and the colour bounds of candidate t.
  Alternative alternative(const SetupTriangle& t, int32_t index, const FragmentRange& f,
                          const OracleFragment& oracle);

  // The oracle's own alternative at (px, py), candidate `index` (the oracle's triangle there), from
  // its block's widths (OwnBlock): false where the block has none.
  bool ownAlternative(const SetupTriangle& t, int32_t index, const Snapped& snapped, int px, int py,
                      const OracleFragment& oracle, Alternative& a);

 private:
  // How far a bilinear sample's texel position (in cache texels, at most `magnitude`) and its
  // value (units of 1/255) may lie from the exact filter's at the exact position, under the model.
  struct SamplerErrors {
    double position, value;
  };
  // A texel's least values of its four channels, then its greatest (doubles, exact).
  using TexelRange = std::array<double, 8>;
  // The most stops bilinearRange evaluates the filter at (their product over both axes).
  static constexpr size_t kMaxBilinearPoints = 64;
  using BilinearStops = Stops<kMaxBilinearPoints + 2>;

  // (s, t) bounds into an alternative, rounded outwards to floats so that they still hold.
  static void setUv(Interval s, Interval t, Alternative& a);

  // A fine derivative's width at one step of attribute k along `axis` from its first centre
  // (cx, cy), whose source box reaches rho: PerturbedTriangle::ratioStepReach plus the float
  // error of a difference (floatStep) and the rounding of the middle's derivative in double.
  static double stepWidth(const OwnBlock& b, const PerturbedTriangle& moves, size_t k, int axis,
                          double cx, double cy, double rho);

  // The OwnBlock of candidate `index` over the block from (bx, by), made by the first pixel that
  // asks (blockClasses has set the block's slot).
  OwnBlock& ownBlock(int32_t index, const Snapped& snapped, int bx, int by);

  // OwnBlock's widths for candidate `index` over the block from (bx, by); not bounded where the
  // triangle is too small for first-order bounds, 1/w may vanish near the block, the texture is
  // sampled without trilinear blending (the level's choice jumps) or the decoding is free.
  void makeOwnBlock(int32_t index, const Snapped& snapped, int bx, int by, OwnBlock& b) const;

  // Level m's bounds over an OwnBlock's reach, made on first use.
  const LevelBounds& levelBounds(OwnBlock& b, int m);

  // The bilinear filter at texel position (x, y) (texel centres at + 0.5) from a level's kept
  // texels, which hold the cell of (x, y).
  static glm::dvec4 keptBilinear(const OwnBlock& b, const LevelBounds& l, double x, double y);

  // The filter over a box of texel positions on a level kept by an OwnBlock, and at a point
  // `at` inside it; false where the box reads texels not kept. Its range: inside one cell between
  // texel centres the filter is bilinear, its bounds at the box's corners; across cells, its value
  // at the point within the Lipschitz bound, and within the texels' hull.
  bool localFilter(const OwnBlock& b, const LevelBounds& l, const WindowBox& box, glm::dvec2 at,
                   LocalFilter& f) const;
  // The colour bounds of ownAlternative from an OwnBlock's levels, over (s, t) and the LOD.
  bool ownColour(OwnBlock& b, Interval s, Interval t, double so, double to, Interval lod,
                 float oracleLodAsDrawn, OwnColour& out);

  // The depth error of candidate t beyond moved corners, in depth units, at a centre (or over a
  // box) where the window plane's terms are at most `planeTerms` and `lambda()` gives the
  // barycentric coordinates. The model's depthUlps and the oracle's own rounding each count 2^-23
  // of the largest of: the depth range [0, 1]; the terms the window plane's evaluation sums
  // (PerturbedTriangle::depthTerms); and the terms any computation of the corners' window z sums,
  // interpolated (WindowCorner::depthTerms). A float evaluation errs relative to its terms, not
  // to the value they sum to, and a corner clipped from a vertex behind the camera is a small
  // difference of huge terms: an H100, which draws such a triangle as the exact polygon, showed a
  // ground plane 2 x 10^5 wide in front of a triangle that is nearer by 3,900 units of 2^-23
  // (data/gpus/nvidia-h100/README.md). Added: a corner the oracle's clipper made moves twice its
  // own float clipping's depth error, by its weight. Infinite where nothing is bounded.
  template <typename BarycentricsOf>
  double depthError(const SetupTriangle& t, double planeTerms, BarycentricsOf lambda) const;

  bool depthPinned() const {
    return model_.coveragePinned() && model_.depthUlps == 0 && model_.depthRoundsToNearest;
  }
  // A window depth as the depth buffer stores it: a 24-bit one rounds (to nearest or either way).
  Interval depthStored(Interval z, DepthFormat format) const;

  // How far the model lets a vertex lie from its float window position: its snapping.
  double snapRadius() const { return std::ldexp(1.0, -model_.subpixelBits); }

  Interval lodRange(Interval dsdx, Interval dtdx, Interval dsdy, Interval dtdy) const;

  // The colour of every (s, t) in the box and LOD in the interval, in units of 1/255.
  Colour shade(Interval s, Interval t, Interval lod);

  // Bilinear lookups of level m over the (s, t) box: every page of level m the box touches, each
  // through its indirection entry (the page or its resident ancestor).
  Colour sampleLevel(Interval s, Interval t, int m);

  Colour samplePage(Interval s, Interval t, glm::ivec2 page, int m);

  // Page `page` of level m's PageMap, from its indirection entry.
  PageMap pageMap(glm::ivec2 page, int m);

  // The corner-weight sampler (Filter::kFixedPointCorners) on a cell of texels c00, c10, c01, c11:
  // its sum differs from the exact bilinear filter at its rounded position only by the rounding of
  // w11 (half a step of 2^-weightBits, or a whole one floored) times c00 - c10 - c01 + c11, since
  // w10, w01 and w00 follow from w11. Callers ask only when cornerStep_ is not 0 (the other
  // members' errors are samplerErrors').
  glm::dvec4 cornerRounding(const glm::dvec4& c00, const glm::dvec4& c10, const glm::dvec4& c01,
                            const glm::dvec4& c11) const {
    return glm::abs(c00 - c10 - c01 + c11) * cornerStep_;
  }
  // The same bound over every texel value the filter could read (|cross term| <= 2 * 255).
  double worstCornerRounding() const { return 510 * cornerStep_; }

  SamplerErrors samplerErrors(double magnitude) const;

  // Bounds of the bilinear filter (texel centres at +0.5, clamped fetches) over a box of texel
  // positions: on each cell between texel centres the filter is bilinear, so its bounds lie at
  // the box's corners and where the box meets the lines through texel centres.
  Colour bilinearRange(Interval x, Interval y);
  // bilinearRange's box where its stops are too many: the hull of the texels it reaches, or every
  // value beyond 16 texels a side.
  Colour texelHull(Interval x, Interval y);
  // bilinearRange's box at its stops: the filter there, plus the corner rounding of its cells.
  Colour bilinearAtStops(Interval x, Interval y, const BilinearStops& xs, const BilinearStops& ys);
  // A texel's range (TexelRange): one value unless the block decoding is free.
  void fetchRange(glm::ivec2 at, TexelRange& r);

  // bilinearRange for a box inside the cell whose lower-left texel is (cx0, cy0), texels of one
  // value: the same operations as the general case on its four texels, at the box's corners.
  Colour bilinearInCell(Interval x, Interval y, double cx0, double cy0);

  // Float colour bounds (units of 1/255) to 8-bit bounds under the model's conversion.
  void store(const Colour& c, glm::u8vec4& lo, glm::u8vec4& hi) const;

  const PrecisionModel& model_;
  SetShading shading_;
  Viewport viewport_;
  TexelSource& source_;
  double finestSide_ = 1;
  double subTexelStep_ = 1;  // a free sampler's texel positions: 2^-subTexelBits texel
  double cornerStep_ = 0;    // the corner-weight sampler's w11 rounding (cornerRounding)
  std::unordered_map<int32_t, Snapped> snapped_;  // by set-up index (elements never move)
  // The four texels of the cells bilinearInCell read last (the cache does not change meanwhile).
  struct Cell {
    glm::ivec2 origin{std::numeric_limits<int>::min()};
    std::array<glm::dvec4, 4> texels;
  };
  std::array<Cell, 2> cells_;
  size_t nextCell_ = 0;
  struct BlockSlot {
    int x = -1, y = -1;
    std::vector<BlockClass> classes;
    std::vector<OwnBlock> own;  // the first ownCount are this block's (kept for their storage)
    size_t ownCount = 0;
  };
  static constexpr int kBlockSlots = Visibility::kTile / Visibility::kBlock;
  std::array<BlockSlot, kBlockSlots> blocks_;
};

}  // namespace vt::reference::sets
