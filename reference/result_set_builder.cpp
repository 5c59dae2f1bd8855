#include "reference/result_set_builder.h"

#include <algorithm>
#include <vector>

#include "reference/set_builder.h"

namespace vt::reference {

using sets::BlockClass;
using sets::Builder;
using sets::PieceCoverage;
using sets::PixelCandidate;
using sets::Snapped;

namespace {

// shares with neighbours surely covers the mesh triangle when each such neighbour is a candidate
// of the same kind: walking across the open edges from piece to piece ends in the piece that holds
// the centre (the fan turns one way around its first vertex), whatever the vertices' moves.
void surelyCoveredByTheirFans(const std::vector<SetupTriangle>& triangles,
                              std::vector<PixelCandidate>& list) {
  const auto fanOf = [&](const PixelCandidate& c) -> const SetupTriangle& {
    return triangles[static_cast<size_t>(c.index)];
  };
  // Whether the fan of set-up triangle `index` has a triangle at fanIndex `position`, or the fan
  // ends before it (then true: nothing to cross to). A fan's triangles are adjacent in the list.
  const auto setUp = [&](int32_t index, int64_t position) {
    const uint32_t primitive = triangles[static_cast<size_t>(index)].primitive;
    int64_t last = -1;
    for (int64_t j = index; j >= 0 && triangles[static_cast<size_t>(j)].primitive == primitive; --j)
      if (triangles[static_cast<size_t>(j)].fanIndex == position) return true;
    for (size_t j = static_cast<size_t>(index);
         j < triangles.size() && triangles[j].primitive == primitive; ++j) {
      if (triangles[j].fanIndex == position) return true;
      last = std::max<int64_t>(last, triangles[j].fanIndex);
    }
    return position > last;
  };
  const auto memberOf = [](const PieceCoverage& p) {
    return p.cover == 2 || (p.boundarySure && p.openFanEdges != 0);
  };
  if (std::none_of(list.begin(), list.end(), [&](const PixelCandidate& c) {
        return c.piece.cover == 1 && memberOf(c.piece);
      }))
    return;
  std::vector<char> member(list.size());
  for (size_t i = 0; i < list.size(); ++i) member[i] = memberOf(list[i].piece);
  // Drop members with an open edge whose neighbour is no member, until none is left to drop.
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (size_t i = 0; i < list.size(); ++i) {
      if (!member[i] || list[i].piece.cover == 2) continue;
      const SetupTriangle& t = fanOf(list[i]);
      for (size_t e = 0; e < 3 && member[i]; ++e) {
        if (!(list[i].piece.openFanEdges & (1u << e))) continue;
        // The neighbour across the edge; a piece that set-up dropped (no area, or no pixel
        // centre) is crossed to the one after it.
        const int step = t.fanNeighbour[e];
        int64_t next = int64_t{t.fanIndex} + step;
        while (next >= 0 && !setUp(list[i].index, next)) next += step;
        bool found = false;
        for (size_t j = 0; j < list.size() && !found; ++j)
          found = member[j] && fanOf(list[j]).primitive == t.primitive &&
                  int64_t{fanOf(list[j]).fanIndex} == next;
        if (!found) {
          member[i] = 0;
          dropped = true;
        }
      }
    }
  }
  for (size_t i = 0; i < list.size(); ++i)
    if (member[i]) list[i].cover = 2;
}

}  // namespace

struct ResultSetBuilder::Impl {
  Impl(const PrecisionModel& model, const SetShading& shading,
       const std::vector<SetupTriangle>& triangles, Viewport viewport, DepthFormat depthFormat,
       TexelSource& source)
      : builder(model, shading, viewport, source), triangles(triangles), depthFormat(depthFormat) {}
  Builder builder;
  const std::vector<SetupTriangle>& triangles;
  DepthFormat depthFormat;
  std::vector<BlockClass> classes;   // of the current pixel's candidates
  std::vector<PixelCandidate> list;  // those that may cover it
};

ResultSetBuilder::ResultSetBuilder(const PrecisionModel& model, const SetShading& shading,
                                   const std::vector<SetupTriangle>& triangles, Viewport viewport,
                                   DepthFormat depthFormat, TexelSource& source)
    : impl_(std::make_unique<Impl>(model, shading, triangles, viewport, depthFormat, source)) {}

ResultSetBuilder::~ResultSetBuilder() = default;

void ResultSetBuilder::append(const Visibility::BlockCandidates& candidates, int px, int py,
                              const OracleFragment& oracle, std::vector<Alternative>& out) {
  Builder& builder = impl_->builder;
  const std::vector<SetupTriangle>& triangles = impl_->triangles;
  const DepthFormat depthFormat = impl_->depthFormat;
  // The candidates' classes over the pixel's block; those that surely cover no centre of it
  // drop out at once.
  std::vector<BlockClass>& classes = impl_->classes;
  classes.clear();
  double front = std::numeric_limits<double>::infinity();  // of those surely covering the block
  constexpr int kBlock = Visibility::kBlock;
  const int bx = px - px % kBlock, by = py - py % kBlock;
  const uint16_t bit = Visibility::BlockCandidates::bitOf(px - bx, py - by);
  std::vector<BlockClass>& known = builder.blockClasses(bx, by, candidates.triangles.size());
  for (size_t i = 0; i < candidates.triangles.size(); ++i) {
    if (!(candidates.pixels[i] & bit)) continue;
    const int32_t index = candidates.triangles[i];
    if (known[i].cover == -2)
      known[i] =
          builder.blockClass(triangles[static_cast<size_t>(index)], index, bx, by, depthFormat);
    const BlockClass& c = known[i];
    if (c.cover == 0) continue;
    classes.push_back(c);
    if (c.cover == 2 && c.z.hi < 1.0) front = std::min(front, c.z.hi);
  }
  // Behind a candidate that surely covers every centre of the block and is surely nearer
  // everywhere in it: at this pixel too it surely beats this one, and beats whatever this one
  // beats, so leaving it out changes nothing; unless it is the oracle's own, or a piece of a
  // clipped fan (the fan's union reads its pieces).
  const auto hidden = [&](const BlockClass& c) {
    const SetupTriangle& t = triangles[static_cast<size_t>(c.index)];
    const bool fanPiece =
        t.fanNeighbour[0] != 0 || t.fanNeighbour[1] != 0 || t.fanNeighbour[2] != 0;
    return front < c.z.lo && c.index != oracle.index && !fanPiece;
  };
  // A lone candidate is compared with the cleared depth alone: where it surely covers the block,
  // the block's depth bounds (which hold the pixel's) decide as well.
  const size_t shown = static_cast<size_t>(std::count_if(
      classes.begin(), classes.end(), [&](const BlockClass& c) { return !hidden(c); }));
  std::vector<PixelCandidate>& list = impl_->list;
  list.clear();
  for (const BlockClass& c : classes) {
    if (hidden(c)) continue;
    const int32_t index = c.index;
    const SetupTriangle& t = triangles[static_cast<size_t>(index)];
    Snapped* s = c.snapped ? c.snapped : builder.snapped(t, index);
    const PieceCoverage piece = c.cover == 2 ? PieceCoverage{2} : builder.coverage(t, s, px, py);
    if (piece.cover == 0) continue;
    const Interval z = shown == 1 && c.cover == 2 ? c.z : builder.depth(t, s, px, py, depthFormat);
    if (!(z.lo < 1.0)) continue;  // never passes GL_LESS against the cleared 1.0
    list.push_back({index, s, piece, z, piece.cover});
  }
  surelyCoveredByTheirFans(triangles, list);
  const auto surelyBeats = [](const PixelCandidate& d, const PixelCandidate& c) {
    if (d.cover != 2 || !(d.z.hi < 1.0)) return false;
    // Points: the pinned depth test, where the earlier drawn triangle wins a tie.
    if (d.z.lo == d.z.hi && c.z.lo == c.z.hi)
      return d.z.lo < c.z.lo || (d.z.lo == c.z.lo && d.index < c.index);
    return d.z.hi < c.z.lo;
  };
  bool mayBeEmpty = true;
  const PixelCandidate* own = nullptr;
  for (const PixelCandidate& c : list) {
    if (c.cover == 2 && c.z.hi < 1.0) mayBeEmpty = false;
    if (c.index == oracle.index) own = &c;
  }
  for (const PixelCandidate& c : list) {
    bool possible = true;
    for (const PixelCandidate& d : list)
      if (&d != &c && surelyBeats(d, c)) possible = false;
    if (!possible && c.index != oracle.index) continue;
    const SetupTriangle& t = triangles[static_cast<size_t>(c.index)];
    Alternative a;
    if (c.index != oracle.index || !c.snapped ||
        !builder.ownAlternative(t, c.index, *c.snapped, px, py, oracle, a))
      a = builder.alternative(t, c.index, builder.fragment(t, c.snapped, px, py), oracle);
    if (c.index != oracle.index)
      a.reasons = (c.cover == 2 && own && own->cover == 2) ? kReasonDepth : kReasonCoverage;
    out.push_back(a);
  }
  if (oracle.index >= 0 && !own) {
    // The oracle's own triangle, should the bounds above have missed it.
    const SetupTriangle& t = triangles[static_cast<size_t>(oracle.index)];
    out.push_back(builder.alternative(
        t, oracle.index, builder.fragment(t, builder.snapped(t, oracle.index), px, py), oracle));
  }
  if (mayBeEmpty || oracle.index < 0) {
    Alternative empty;
    empty.triangle = -1;
    empty.reasons = oracle.index < 0 ? 0 : kReasonCoverage;
    out.push_back(empty);
  }
}

}  // namespace vt::reference
