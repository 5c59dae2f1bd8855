#include "calibrate/coverage_fit.h"

#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>

#include "common/random_draws.h"

namespace vt::calibrate {
namespace {

// Probe coordinates are multiples of 2^-12 pixel below 1024: 22 significant bits, exact in the
// float clip-space positions and in every product the edge tests below form in double.
constexpr double kProbeStep = 0x1p-12;
constexpr int kCell = 12;

double rounded(double v, SnapRounding rounding) {
  switch (rounding) {
    case SnapRounding::kHalfEven:
      return std::nearbyint(v);  // the default mode: to nearest even
    case SnapRounding::kHalfUp:
      return std::floor(v + 0.5);
    case SnapRounding::kFloor:
      return std::floor(v);
    case SnapRounding::kCeil:
      return std::ceil(v);
    case SnapRounding::kNone:
      return v;
  }
  return v;
}

double snapped(double x, const CoverageHypothesis& h) {
  if (h.rounding == SnapRounding::kNone) return x;
  const double grid = std::ldexp(1.0, h.subpixelBits);
  return 0.5 + rounded((x - 0.5) * grid, h.rounding) / grid;
}

const char* roundingName(SnapRounding rounding) {
  switch (rounding) {
    case SnapRounding::kHalfEven:
      return "round half to even";
    case SnapRounding::kHalfUp:
      return "round half up";
    case SnapRounding::kFloor:
      return "rounded down";
    case SnapRounding::kCeil:
      return "rounded up";
    case SnapRounding::kNone:
      return "not snapped";
  }
  return "";
}

}  // namespace

std::string describe(const CoverageHypothesis& h) {
  std::string text =
      h.rounding == SnapRounding::kNone
          ? std::string("vertices not snapped")
          : std::to_string(h.subpixelBits) + " sub-pixel bits, " + roundingName(h.rounding);
  text += std::string(", centres on ") + (h.leftEdgesIn ? "left" : "right") + " and " +
          (h.bottomEdgesIn ? "bottom" : "top") + " edges inside";
  return text;
}

std::vector<CoverageHypothesis> coverageHypotheses() {
  std::vector<CoverageHypothesis> all;
  for (const bool left : {true, false})
    for (const bool bottom : {true, false}) {
      for (int bits = 1; bits <= 14; ++bits)
        for (const SnapRounding r : {SnapRounding::kHalfEven, SnapRounding::kHalfUp,
                                     SnapRounding::kFloor, SnapRounding::kCeil})
          all.push_back({bits, r, left, bottom});
      all.push_back({0, SnapRounding::kNone, left, bottom});
    }
  return all;
}

namespace {

// The probe's vertices as the hypothetical rasterizer sees them, counter-clockwise (y up: the
// interior left of each edge); nullopt when snapping leaves no area (nothing is drawn).
std::optional<std::array<glm::dvec2, 3>> setUp(const CoverageHypothesis& h,
                                               const CoverageProbe& probe) {
  std::array<glm::dvec2, 3> v;
  for (int i = 0; i < 3; ++i)
    v[i] = {snapped(probe.vertices[i].x, h), snapped(probe.vertices[i].y, h)};
  const glm::dvec2 e1 = v[1] - v[0], e2 = v[2] - v[0];
  const double area = e1.x * e2.y - e1.y * e2.x;
  if (area == 0) return std::nullopt;
  if (area < 0) std::swap(v[1], v[2]);
  return v;
}

bool coversSetUp(const CoverageHypothesis& h, const std::array<glm::dvec2, 3>& v, int px, int py) {
  const glm::dvec2 p(px + 0.5, py + 0.5);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 a = v[i], b = v[(i + 1) % 3];
    const glm::dvec2 d = b - a;
    const double value = d.x * (p.y - a.y) - d.y * (p.x - a.x);
    if (value > 0) continue;
    if (value < 0) return false;
    // On the edge: the interior is to its right when it runs down (a left edge); a horizontal
    // edge running right has the interior above it (a bottom edge).
    const bool inside = d.y != 0 ? (d.y < 0) == h.leftEdgesIn : (d.x > 0) == h.bottomEdgesIn;
    if (!inside) return false;
  }
  return true;
}

}  // namespace

bool covers(const CoverageHypothesis& h, const CoverageProbe& probe, int px, int py) {
  const auto v = setUp(h, probe);
  return v && coversSetUp(h, *v, px, py);
}

std::optional<Coverage> coverageMember(const CoverageHypothesis& h) {
  vt::SnapRounding rounding = vt::SnapRounding::kHalfEven;
  switch (h.rounding) {
    case SnapRounding::kNone:
      return std::nullopt;
    case SnapRounding::kHalfUp:
      rounding = vt::SnapRounding::kHalfUp;
      break;
    case SnapRounding::kFloor:
      rounding = vt::SnapRounding::kFloor;
      break;
    case SnapRounding::kCeil:
      rounding = vt::SnapRounding::kCeil;
      break;
    case SnapRounding::kHalfEven:
      break;
  }
  return Coverage{CoverageRule::kSnappedEdges, h.subpixelBits, rounding, h.leftEdgesIn,
                  h.bottomEdgesIn};
}

std::vector<CoverageProbe> coverageProbes(unsigned seed, Viewport viewport) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto pick = [&](int lo, int hi) {  // a whole number in [lo, hi]
    return lo + static_cast<int>(unit(random) * (hi - lo + 1)) % (hi - lo + 1);
  };
  // 0, or +-k * 2^-12 with k log-uniform in [1, 2048]: every grid's rounding ties among them.
  const auto offset = [&]() {
    if (pick(0, 3) == 0) return 0.0;
    const double k = std::floor(std::exp2(11.0 * unit(random)));
    return (pick(0, 1) == 0 ? -k : k) * kProbeStep;
  };
  std::vector<CoverageProbe> probes;
  for (int cy = 0; cy + kCell <= viewport.height; cy += kCell)
    for (int cx = 0; cx + kCell <= viewport.width; cx += kCell) {
      CoverageProbe probe;
      probe.cellMin = {cx, cy};
      probe.cellMax = {cx + kCell, cy + kCell};
      const glm::dvec2 centre(cx + kCell / 2 + 0.5, cy + kCell / 2 + 0.5);
      // A pixel centre at most `reach` pixels from the cell's centre, moved by small offsets.
      // (The offsets are drawn before the whole pixels: the records' order, common/random_draws.h.)
      const auto near = [&](int reach) {
        const glm::dvec2 moved = drawPoint(offset);
        const glm::dvec2 pixels = drawPoint([&] { return double(pick(-reach, reach)); });
        return centre + pixels + moved;
      };
      auto& v = probe.vertices;
      switch (probes.size() % 5) {
        case 0:  // a small triangle
          v = {near(3), near(3), near(3)};
          break;
        case 1: {  // a sliver: the third vertex next to the middle of the other two
          v[0] = near(4);
          v[1] = 2.0 * centre - v[0];
          v[2] = centre + drawPoint(offset);
          break;
        }
        case 2: {  // a right triangle: a vertical and a horizontal edge near centres
          const glm::dvec2 corner = near(1);
          const auto leg = [&] {  // 1 to 3 pixels either way, moved by an offset
            const int length = pick(1, 3);
            const int sign = pick(0, 1) ? 1 : -1;
            return length * sign + offset();
          };
          v = {corner, corner + glm::dvec2(leg(), 0.0), corner + glm::dvec2(0.0, leg())};
          break;
        }
        case 3: {  // an edge exactly through the cell's centre (its ends mirror each other)
          v[0] = near(4);
          v[1] = 2.0 * centre - v[0];
          v[2] = near(4);
          break;
        }
        default:  // below a pixel: within half a pixel of the centre
          v = {centre + drawPoint(offset), centre + drawPoint(offset), centre + drawPoint(offset)};
          break;
      }
      probes.push_back(probe);
    }
  return probes;
}

ClipSpaceMesh coverageMesh(const std::vector<CoverageProbe>& probes, Viewport viewport) {
  const auto powerOfTwo = [](int n) { return n > 0 && n <= 1024 && (n & (n - 1)) == 0; };
  if (!powerOfTwo(viewport.width) || !powerOfTwo(viewport.height))
    throw std::invalid_argument("coverage probes need a viewport of powers of two up to 1024");
  ClipSpaceMesh mesh;
  for (const CoverageProbe& probe : probes)
    for (const glm::dvec2& p : probe.vertices) {
      mesh.vertices.push_back(
          {glm::vec4(static_cast<float>(p.x / (viewport.width / 2) - 1.0),
                     static_cast<float>(p.y / (viewport.height / 2) - 1.0), 0.0f, 1.0f),
           glm::vec2(0.0f)});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  return mesh;
}

int CoverageFit::coarsestBits() const {
  int coarsest = 0;
  for (const CoverageHypothesis& h : consistent) {
    const int bits = h.rounding == SnapRounding::kNone ? 12 : h.subpixelBits;
    if (coarsest == 0 || bits < coarsest) coarsest = bits;
  }
  return coarsest;
}

CoverageFit fitCoverage(const std::vector<CoverageProbe>& probes, Viewport viewport,
                        const std::vector<int32_t>& drawn) {
  const auto expect = [&](bool condition) {
    if (!condition)
      throw std::invalid_argument("coverage fit: the readback does not fit the probes");
  };
  expect(drawn.size() ==
         static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height));
  for (const CoverageProbe& probe : probes)
    expect(probe.cellMin.x >= 0 && probe.cellMin.y >= 0 && probe.cellMax.x <= viewport.width &&
           probe.cellMax.y <= viewport.height);
  // Mismatching pixels of a hypothesis, counting no further than `limit`.
  const auto mismatches = [&](const CoverageHypothesis& h, uint64_t limit) {
    uint64_t count = 0;
    for (size_t k = 0; k < probes.size() && count < limit; ++k) {
      const CoverageProbe& probe = probes[k];
      const auto v = setUp(h, probe);
      for (int py = probe.cellMin.y; py < probe.cellMax.y; ++py)
        for (int px = probe.cellMin.x; px < probe.cellMax.x; ++px) {
          const size_t i = static_cast<size_t>(py) * static_cast<size_t>(viewport.width) +
                           static_cast<size_t>(px);
          count += (v && coversSetUp(h, *v, px, py)) != (drawn[i] == static_cast<int32_t>(k));
        }
    }
    return count;
  };
  CoverageFit fit;
  for (const CoverageProbe& probe : probes)
    fit.pixels += static_cast<uint64_t>(probe.cellMax.x - probe.cellMin.x) *
                  static_cast<uint64_t>(probe.cellMax.y - probe.cellMin.y);
  const std::vector<CoverageHypothesis> all = coverageHypotheses();
  for (const CoverageHypothesis& h : all)
    if (mismatches(h, 1) == 0) fit.consistent.push_back(h);
  if (fit.consistent.empty()) {
    fit.closestMismatches = fit.pixels + 1;
    for (const CoverageHypothesis& h : all) {
      const uint64_t count = mismatches(h, fit.closestMismatches);
      if (count < fit.closestMismatches) {
        fit.closest = h;
        fit.closestMismatches = count;
      }
    }
  }
  return fit;
}

}  // namespace vt::calibrate
