// Which triangle may own a pixel under a precision model (set_builder.h): each candidate's corners
// as the model lets them move, its coverage of the pixel centre and its window depth there, per
// pixel and, where one decision holds for all, per 4 x 4 block.

#include <algorithm>
#include <cmath>

#include "reference/set_builder.h"

namespace vt::reference::sets {

CornerBoxes cornerBoxes(const SetupTriangle& t, double radius, Viewport viewport) {
  CornerBoxes b;
  const double extent = std::max(viewport.width, viewport.height);
  for (size_t i = 0; i < 3; ++i) {
    const double window =
        4 * kFloatUlp * (std::fabs(t.corners[i].x) + std::fabs(t.corners[i].y) + extent);
    const double clipped = 2.0 * t.corners[i].clipError;
    b.x[i] = Interval::around(t.corners[i].x, radius + window + clipped);
    b.y[i] = Interval::around(t.corners[i].y, radius + window + clipped);
  }
  return b;
}

double largestRadius(const CornerBoxes& b) {
  double r = 0;
  for (size_t i = 0; i < 3; ++i) r = std::max({r, b.x[i].width() / 2, b.y[i].width() / 2});
  return r;
}

Barycentrics barycentrics(const CornerBoxes& b, double cx, double cy) {
  Barycentrics r;
  const Interval area =
      (b.x[1] - b.x[0]) * (b.y[2] - b.y[0]) - (b.x[2] - b.x[0]) * (b.y[1] - b.y[0]);
  if (area.containsZero()) {
    r.degenerate = true;
    return r;
  }
  for (size_t i = 0; i < 3; ++i) {
    const size_t j = (i + 1) % 3, k = (i + 2) % 3;
    // e_i(p) = (x_k - x_j) (p_y - y_j) - (y_k - y_j) (p_x - x_j)
    const Interval e = (b.x[k] - b.x[j]) * (Interval::point(cy) - b.y[j]) -
                       (b.y[k] - b.y[j]) * (Interval::point(cx) - b.x[j]);
    r.atCentre[i] = widen(e / area);
    r.ddx[i] = widen(-(b.y[k] - b.y[j]) / area);
    r.ddy[i] = widen((b.x[k] - b.x[j]) / area);
  }
  return r;
}

Snapped* Builder::snapped(const SetupTriangle& t, int32_t index) {
  if (!movesVertices()) return nullptr;
  const auto found = snapped_.find(index);
  if (found != snapped_.end()) return &found->second;
  const CornerBoxes boxes = cornerBoxes(t, snapRadius(), viewport_);
  const PerturbedTriangle perturbed(t, largestRadius(boxes));
  AffinePlane s, tt;
  if (perturbed.bounded()) {
    s = perturbed.attribute({t.corners[0].sw, t.corners[1].sw, t.corners[2].sw});
    tt = perturbed.attribute({t.corners[0].tw, t.corners[1].tw, t.corners[2].tw});
  }
  return &snapped_.emplace(index, Snapped{boxes, perturbed, s, tt, {}, {}, kNaN, 0, {}})
              .first->second;
}

std::vector<BlockClass>& Builder::blockClasses(int bx, int by, size_t count) {
  constexpr int kBlock = Visibility::kBlock;
  BlockSlot& slot = blocks_[static_cast<size_t>((bx / kBlock) % kBlockSlots)];
  if (slot.x != bx || slot.y != by || slot.classes.size() != count) {
    slot.x = bx;
    slot.y = by;
    slot.classes.assign(count, BlockClass{});
    slot.ownCount = 0;
  }
  return slot.classes;
}

BlockClass Builder::blockClass(const SetupTriangle& t, int32_t index, int bx, int by,
                               DepthFormat format) {
  constexpr int kBlock = Visibility::kBlock;
  BlockClass c;
  c.index = index;
  c.cover = -1;
  if (model_.coveragePinned()) return c;
  Snapped* s = c.snapped = snapped(t, index);
  if (!s->perturbed.bounded()) return c;
  const WindowBox box =
      s->perturbed.sourceBoxOver(bx + 0.5, by + 0.5, bx + kBlock - 0.5, by + kBlock - 0.5);
  c.cover = 2;
  for (size_t i = 0; i < 3 && c.cover != 0; ++i) {
    const Interval lambda = s->perturbed.barycentric(i, box);
    if (lambda.hi < 0)
      c.cover = 0;
    else if (!(lambda.lo > 0))
      c.cover = -1;
  }
  if (c.cover != 0) {
    // What depth() bounds at each centre: its steps over the block's box instead of a centre's
    // source box, with the arithmetic's own window depth at every centre of the block.
    Interval own = {std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity()};
    for (int y = by; y < by + kBlock; ++y)
      for (int x = bx; x < bx + kBlock; ++x)
        own = hull(own, Interval::point(windowDepth(t, x, y, model_.arithmetic)));
    double planeTerms = 0;
    for (const double cx : {bx + 0.5, bx + kBlock - 0.5})
      for (const double cy : {by + 0.5, by + kBlock - 0.5})
        planeTerms = std::max(planeTerms, s->perturbed.depthTerms(cx, cy));
    const Interval z =
        widen(s->perturbed.depth(box), 0,
              depthError(t, planeTerms, [&] { return s->perturbed.barycentrics(box); }));
    c.z = depthStored(hull(z, own), format);
  }
  return c;
}

template <typename BarycentricsOf>
double Builder::depthError(const SetupTriangle& t, double planeTerms, BarycentricsOf lambda) const {
  double scale = std::max(1.0, planeTerms);
  double clipped = 0;
  const std::array<WindowCorner, 3>& c = t.corners;
  // A corner within the depth range has terms of at most 1, so its share never passes the range.
  if (std::max({c[0].depthTerms, c[1].depthTerms, c[2].depthTerms}) > 1 ||
      std::max({c[0].clipDepthError, c[1].clipDepthError, c[2].clipDepthError}) > 0) {
    const std::array<Interval, 3> l = lambda();
    double cornerTerms = 0;
    for (size_t j = 0; j < 3; ++j) {
      cornerTerms += c[j].depthTerms * l[j].magnitude();
      clipped += 2.0 * c[j].clipDepthError * l[j].magnitude();
    }
    scale = std::max(scale, cornerTerms);
  }
  const double error = (model_.depthUlps + 1) * kFloatUlp * scale + clipped;
  return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
}

PieceCoverage Builder::coverage(const SetupTriangle& t, Snapped* s, int px, int py) const {
  if (model_.coveragePinned()) return {t.covers(px, py) ? 2 : 0};
  std::array<Interval, 3> lambda;
  if (s->perturbed.bounded()) {
    // Each coordinate only while none so far is surely negative (most candidates are outside).
    const WindowBox& source = s->sourceAt(px + 0.5, py + 0.5);
    for (size_t i = 0; i < 3; ++i) {
      lambda[i] = s->perturbed.barycentric(i, source);
      if (lambda[i].hi < 0) return {0};
    }
  } else {
    const Barycentrics l = barycentrics(s->boxes, px + 0.5, py + 0.5);
    if (l.degenerate) return {1};
    lambda = l.atCentre;
  }
  PieceCoverage c{2};
  for (size_t i = 0; i < 3; ++i) {
    // Surely outside any edge: not this piece. Beyond an edge inside a clipped fan lies the
    // fan's next piece, a candidate of its own with the same planes.
    if (lambda[i].hi < 0) return {0};
    if (lambda[i].lo > 0) continue;
    // On the centre's side or not: the tie rule decides on an edge of the mesh triangle; on an
    // edge inside the fan the pixel is this piece's or its neighbour's (appendResultSet).
    c.cover = 1;
    if (t.fanNeighbour[i] != 0)
      c.openFanEdges = static_cast<uint8_t>(c.openFanEdges | (1u << i));
    else
      c.boundarySure = false;
  }
  return c;
}

Interval Builder::depth(const SetupTriangle& t, Snapped* s, int px, int py,
                        DepthFormat format) const {
  const double own = windowDepth(t, px, py, model_.arithmetic);
  if (depthPinned()) return Interval::point(own);
  const PerturbedTriangle& perturbed = s->perturbed;
  const Barycentrics l =
      perturbed.bounded() ? Barycentrics{} : barycentrics(s->boxes, px + 0.5, py + 0.5);
  Interval z = Interval::everything();
  if (perturbed.bounded() || !l.degenerate) {
    const WindowBox source = perturbed.bounded() ? s->sourceAt(px + 0.5, py + 0.5) : WindowBox{};
    z = perturbed.bounded() ? perturbed.depth(source)
                            : interpolate(l, t.corners[0].z, t.corners[1].z, t.corners[2].z).value;
    const double error = depthError(t, perturbed.depthTerms(px + 0.5, py + 0.5), [&] {
      return perturbed.bounded() ? perturbed.barycentrics(source) : l.atCentre;
    });
    z = std::isfinite(error) ? widen(z, 0, error) : Interval::everything();
  }
  return depthStored(hull(z, Interval::point(own)), format);
}

Interval Builder::depthStored(Interval z, DepthFormat format) const {
  if (format == DepthFormat::kDepth24)
    z = widen(z, 0, (model_.depthRoundsToNearest ? 0.5 : 1.0) / 16777215.0);
  return clamp(z, 0, 1);
}

}  // namespace vt::reference::sets
