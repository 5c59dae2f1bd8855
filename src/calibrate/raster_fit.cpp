#include "calibrate/raster_fit.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <type_traits>

#include "calibrate/coverage_fit.h"
#include "calibrate/float_bits.h"
#include "calibrate/plane_probes.h"
#include "calibrate/probe_texture.h"
#include "common/random_draws.h"
#include "probes/function_sweeps.h"
#include "probes/probe_draws.h"
#include "reference/renderer.h"
#include "reference/visibility.h"
#include "render/precision_model.h"
#include "scene/camera.h"
#include "scene/captured_triangles.h"
#include "scene/mesh.h"

namespace vt::calibrate {
namespace {}  // namespace

Frame oracleFrame(const ClipSpaceMesh& mesh, const reference::ResidentTexture& texture,
                  Viewport viewport, const Arithmetic& arithmetic, DepthFormat format) {
  RenderSettings settings;
  settings.debugChannels = true;
  settings.viewport = viewport;
  settings.arithmetic = arithmetic;
  settings.depthFormat = format;
  return reference::renderFrame(mesh, texture, settings);
}

void compareRaster(const RasterReadback& gl, const Frame& oracle, RasterCounts& c) {
  for (size_t i = 0; i < oracle.triangle.size(); ++i) {
    ++c.pixels;
    if (gl.triangle[i] != oracle.triangle[i]) {
      ++c.coverage;
      ++c.differing;
      continue;
    }
    if (gl.triangle[i] < 0) continue;
    ++c.shared;
    bool differs = false;
    for (int k = 0; k < 2; ++k) {
      differs |= !sameBits(gl.uv[i][k], oracle.uv[i][k]);
      c.attributeDistance +=
          floatsBetween(gl.uv[i][k], oracle.uv[i][k], RasterCounts::kDistanceCap);
    }
    for (int k = 0; k < 4; ++k) {
      differs |= !sameBits(gl.derivatives[i][k], oracle.derivatives[i][k]);
      c.attributeDistance +=
          floatsBetween(gl.derivatives[i][k], oracle.derivatives[i][k], RasterCounts::kDistanceCap);
    }
    const bool depthDiffers = !sameBits(gl.depth[i], oracle.depth[i]);
    c.depthDistance += floatsBetween(gl.depth[i], oracle.depth[i], RasterCounts::kDistanceCap);
    c.attributes += differs;
    c.depth += depthDiffers;
    c.differing += differs || depthDiffers;
  }
}

std::string nameOf(const Coverage& c) {
  if (c.rule == CoverageRule::kScanlineSpans) return "scanline_spans";
  return std::to_string(c.subpixelBits) + "_bits_" +
         std::string(vt::nameOf(kSnapRoundingNames, c.rounding)) + "_" +
         (c.leftEdgesIn ? "left" : "right") + "_" + (c.bottomEdgesIn ? "bottom" : "top");
}

namespace {

// Coverage alone: the snapping rasterizers the coverage probes leave consistent.
struct GridResult {
  ParameterFit fit;
  std::vector<Coverage> candidates;
  int coarsestBits = 0;
};

GridResult fitGrid() {
  const Viewport viewport{1024, 512};
  const std::vector<CoverageProbe> probes = coverageProbes(12, viewport);
  const RasterReadback drawn = drawTriangles(coverageMesh(probes, viewport), viewport);
  const CoverageFit fit = fitCoverage(probes, viewport, drawn.triangle);
  GridResult result;
  result.coarsestBits = fit.coarsestBits();
  const std::string over = std::to_string(fit.pixels) + " pixels of " +
                           std::to_string(probes.size()) +
                           " probe triangles at 2^-12 offsets around pixel centres";
  std::string finding;
  if (fit.consistent.empty()) {
    finding =
        "no snapping grid of 1 to 14 bits nor unsnapped vertices with a fixed tie rule "
        "covers the " +
        over + " as drawn; closest: " + describe(fit.closest) + " (" +
        std::to_string(fit.closestMismatches) + " pixels differ)";
  } else {
    finding =
        "the " + over + " are covered as drawn by " +
        (fit.consistent.size() == 1 ? std::string("exactly one rasterizer of the grid family")
                                    : std::to_string(fit.consistent.size()) +
                                          " rasterizers of the grid family, the coarsest " +
                                          std::to_string(result.coarsestBits) + " sub-pixel bits") +
        ":";
    for (size_t i = 0; i < fit.consistent.size() && i < 6; ++i)
      finding += (i ? "; " : " ") + describe(fit.consistent[i]);
    if (fit.consistent.size() > 6) finding += "; ...";
  }
  result.fit.parameter = "subpixel_bits";
  result.fit.finding = finding;
  result.fit.probe = "3,570 triangles at 2^-12-pixel offsets around pixel centres";
  result.fit.probes = fit.pixels;
  result.fit.mismatches = fit.consistent.empty() ? fit.closestMismatches : 0;
  result.fit.pinned = fit.consistent.size() == 1;
  result.fit.fromGl45 = fit.consistent.empty();
  result.fit.chosen = fit.consistent.empty() ? "" : describe(fit.consistent.front());
  // The snapping members among them (a few: coverage at centres cannot tell b bits rounded from
  // b + 1 truncated), and the closest where none is consistent.
  std::vector<CoverageHypothesis> hypotheses = fit.consistent;
  if (hypotheses.empty()) hypotheses.push_back(fit.closest);
  for (const CoverageHypothesis& h : hypotheses) {
    const std::optional<Coverage> member = coverageMember(h);
    if (member && result.candidates.size() < 4) result.candidates.push_back(*member);
  }
  Coverage spans;
  spans.rule = CoverageRule::kScanlineSpans;
  result.candidates.push_back(spans);
  return result;
}

// Triangles on the near plane: every vertex at z = -w, inside by the clip test, whose window z
// z * (1 / w) * 0.5 + 0.5 is 0 or, where 1 / w rounds up, just below it; half of them tilted a
// hair away from the plane. Their pixels' window z is 0 up to rounding: where it goes below 0 a
// clamp shows, and where it is -0.0 the + 0.0 offset term (docs/design.md section 7, rule 7),
// which the random triangles rarely reach.
ClipSpaceMesh nearPlaneTriangles(unsigned seed, int triangles) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), wRange(0.3f, 3.0f), hair(0.0f, 1e-6f);
  ClipSpaceMesh mesh;
  for (int k = 0; k < triangles; ++k) {
    const glm::vec2 centre = 0.6f * drawPoint([&] { return unit(random); });
    for (int corner = 0; corner < 3; ++corner) {
      const float w = wRange(random);
      const glm::vec2 xy = centre + 0.5f * drawPoint([&] { return unit(random); });
      const float z = k % 2 ? -w : -w * (1.0f - hair(random));
      mesh.vertices.push_back(
          {{xy.x * w, xy.y * w, z, w}, {0.5f + 0.5f * unit(random), 0.5f + 0.5f * unit(random)}});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  }
  return mesh;
}

// `shared` with each triangle's own vertices (probe_draws.h).
ClipSpaceMesh withOwnVertices(const ClipSpaceMesh& shared) {
  ClipSpaceMesh clip;
  for (const uint32_t index : shared.indices) {
    clip.vertices.push_back(shared.vertices[index]);
    clip.indices.push_back(static_cast<uint32_t>(clip.vertices.size() - 1));
  }
  return clip;
}

// A plane reaching the horizon under strong perspective, cut by the near plane, its two
// triangles each with their own vertices (probe_draws.h). Its triangles span the screen, so
// vertices moved within a sub-pixel grid move the texture coordinates by almost nothing, while
// the plane evaluation's terms dwarf the values they sum to: what the implementation's
// interpolation arithmetic does shows here, unmasked by vertex movement. On random triangles an
// H100's coordinates stayed within what its 8-bit grid explains, and its horizon captures did not
// (docs/gpus.md).
struct HorizonView {
  float height;      // camera above the plane
  float yawDegrees;  // about the plane's normal
  float rollDegrees;
  float offset;       // the plane's centre from the camera, along its s axis, in plane widths
  float tiltDegrees;  // the plane's tilt about its t axis (89.9: nearly edge-on)
};

ClipSpaceMesh horizonPlane(const HorizonView& view, Viewport viewport) {
  const float width = 2e5f;
  const float tilt = glm::radians(view.tiltDegrees);
  const glm::vec3 along(std::cos(tilt), std::sin(tilt), 0.0f), depth(0.0f, 0.0f, -1.0f);
  const glm::vec3 origin =
      -0.5f * width * along + 0.5f * width * glm::vec3(0, 0, 1) + view.offset * width * along;
  Mesh mesh;
  for (const glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
    mesh.positions.push_back(origin + c.x * width * along + c.y * width * depth);
    mesh.uvs.emplace_back(c.x, 1.0f - c.y);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  const float yaw = glm::radians(view.yawDegrees), roll = glm::radians(view.rollDegrees);
  Camera camera;
  camera.position = {0.0f, view.height, 0.0f};
  const glm::vec3 forward(std::sin(yaw), -std::tan(glm::radians(30.0f)) / 32.0f, -std::cos(yaw));
  camera.target = camera.position + forward;
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  camera.up = std::cos(roll) * glm::vec3(0, 1, 0) + std::sin(roll) * right;
  camera.nearPlane = 0.05f;
  camera.farPlane = 1e7f;
  return withOwnVertices(toClipSpace(mesh, camera, viewport));
}

// Two planes 2 x 10^5 wide around the camera, so that each of their triangles has a vertex
// behind it: the ground, and a second plane through a line on the ground `distance` ahead,
// turned `lineDegrees` from the screen's horizontal and tilted `tiltRadians` about it. They cross
// on that line, where their depths differ by less than any bound; along it the implementation's
// depth error decides which one shows. A rasterizer that clips nothing evaluates such a
// triangle's depth from homogeneous barycentrics whose terms dwarf the value, and a clipper
// computes its corners as small differences of huge coordinates: an H100 showed a plane like
// these in front of a triangle nearer by 3,900 units of 2^-23 (data/gpus/nvidia-h100/README.md).
struct CrossingPlanes {
  float height;  // camera above the ground
  float distance;
  float lineDegrees;
  float tiltRadians;
};

ClipSpaceMesh planesBehindTheCamera(const CrossingPlanes& view, Viewport viewport) {
  const float half = 1e5f;
  const float turn = glm::radians(view.lineDegrees);
  const glm::vec3 line(std::cos(turn), 0.0f, std::sin(turn));
  const glm::vec3 across(-line.z, 0.0f, line.x);  // on the ground, perpendicular to the line
  const glm::vec3 tilted =
      std::cos(view.tiltRadians) * across + std::sin(view.tiltRadians) * glm::vec3(0, 1, 0);
  const glm::vec3 onLine(0.0f, 0.0f, -view.distance);
  Mesh mesh;
  for (const glm::vec3& side : {across, tilted}) {
    const uint32_t first = static_cast<uint32_t>(mesh.positions.size());
    for (const glm::vec2 c :
         {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      mesh.positions.push_back(onLine + c.x * half * line + c.y * half * side);
      mesh.uvs.emplace_back(0.5f + 0.5f * c.x, 0.5f + 0.5f * c.y);
    }
    for (const uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + k);
  }
  Camera camera;
  camera.position = {0.0f, view.height, 0.0f};
  camera.target = camera.position + glm::vec3(0.0f, -0.15f, -1.0f);
  camera.nearPlane = 0.05f;
  camera.farPlane = 1e5f;
  return withOwnVertices(toClipSpace(mesh, camera, viewport));
}

// A probe mesh with its viewport and what the implementation drew of it.
struct DrawnProbe {
  ClipSpaceMesh mesh;
  Viewport viewport;
  RasterReadback gl;
};

// What the result sets of `model` leave unexplained of the implementation's readbacks: pixels
// whose triangle no alternative names, and pixels whose (s, t) lies outside its alternative's
// interval.
struct SetResiduals {
  uint64_t unexplainedOwners = 0;
  uint64_t attributesOutside = 0;
};

SetResiduals setResiduals(const PrecisionModel& model, const std::vector<DrawnProbe>& drawn,
                          const reference::ResidentTexture& texture) {
  SetResiduals r;
  for (const auto& [mesh, viewport, gl] : drawn) {
    RenderSettings settings;
    settings.viewport = viewport;
    applyModel(settings, model);
    const Frame frame = reference::renderFrame(mesh, texture, settings);
    for (size_t i = 0; i < gl.triangle.size(); ++i) {
      const Alternative* match = nullptr;
      for (uint32_t a = frame.sets.offsets[i]; a < frame.sets.offsets[i + 1]; ++a)
        if (frame.sets.alternatives[a].triangle == gl.triangle[i])
          match = &frame.sets.alternatives[a];
      if (!match) {
        ++r.unexplainedOwners;
        continue;
      }
      if (gl.triangle[i] < 0) continue;
      bool outside = false;
      for (int k = 0; k < 2; ++k) {
        const float uv = std::clamp(gl.uv[i][k], 0.0f, 1.0f);
        outside |= uv < match->uvLo[k] || uv > match->uvHi[k];
      }
      r.attributesOutside += outside;
    }
  }
  return r;
}

// The smallest whole bound b >= 1 with admits(b) (admits grows with b), doubling from 1 up to
// `limit` and then halving the interval; 0 where admits(0) already holds; `limit` doubled until
// it admits (or 2^30) where nothing up to `limit` does.
template <typename Admits>
double smallestBound(Admits admits, double limit) {
  if (admits(0.0)) return 0;
  double lo = 0, hi = 1;
  bool admitted = admits(hi);
  while (!admitted && hi < 0x1p30) {
    lo = hi;
    hi = hi < limit ? std::min(2 * hi, limit) : 2 * hi;
    admitted = admits(hi);
  }
  while (hi - lo > 1) {
    const double mid = std::floor((lo + hi) / 2);
    (admits(mid) ? hi : lo) = mid;
  }
  return hi;
}

// One combination of the rasterization members.
struct Combination {
  Arithmetic arithmetic;
  RasterCounts counts;
};

// The probes of the combined fit, in words, and what memberSummary counts for their families.
const char* const kRasterProbe =
    "360 random triangles (slivers, perspective, near-plane clipping, a "
    "coplanar pair), 60 cut just behind the near plane, three planes to the horizon, two "
    "pairs of crossing planes and a ground under a triangle, with vertices behind the camera, "
    "at 160 x 120";
// Added to it where the folder holds the plane group (plane_probes.h).
const char* const kPlaneGroupProbe =
    "; and one triangle on the 1/256 grid at w = 1, shifted by 1 to 512 pixels, its depths near "
    "1 and near 2^-10, its vertices rotated, at w 0.5, 2 and 3";
const char* const kPixelsCounted =
    " pixels, in coverage, coordinates or depth, with the member's best combination";

// Every combination of the coverage candidates and the other families' members, on `base`.
std::vector<Combination> allCombinations(const Arithmetic& base,
                                         const std::vector<Coverage>& coverages) {
  // The perspective members; reciprocal_times also with the measured reciprocal, where the shader
  // fit offers one (shader_math_fit.h).
  std::vector<std::pair<Perspective, Reciprocal>> perspectives;
  for (const auto& [perspective, name] : kPerspectiveNames) {
    perspectives.push_back({perspective, Reciprocal{}});
    if (perspective == Perspective::kReciprocalTimes && base.reciprocal.table)
      perspectives.push_back({perspective, base.reciprocal});
  }
  std::vector<Combination> combinations;
  for (const Coverage& coverage : coverages)
    for (const bool fusedViewport : {true, false})
      for (const auto& [setup, setupName] : kPlaneSetupNames)
        for (const auto& [positions, positionsName] : kPlanePositionsNames) {
          // Scanline spans snap no position to set planes up through.
          if (positions == PlanePositions::kSnapped && coverage.rule != CoverageRule::kSnappedEdges)
            continue;
          for (const auto& [evaluation, evaluationName] : kPlaneEvaluationNames)
            for (const auto& [perspective, reciprocal] : perspectives)
              for (const bool offsetAndClamp : {true, false}) {
                Arithmetic a = base;
                a.coverage = coverage;
                a.fusedViewport = fusedViewport;
                a.planeSetup = setup;
                a.planePositions = positions;
                a.planeEvaluation = evaluation;
                a.perspective = perspective;
                a.reciprocal = reciprocal;
                a.depth.offsetAndClamp = offsetAndClamp;
                combinations.push_back({a, {}});
              }
        }
  return combinations;
}

// The meshes of kRasterProbe, in the order they are drawn.
std::vector<ClipSpaceMesh> rasterProbeMeshes(Viewport viewport) {
  std::vector<ClipSpaceMesh> meshes;
  for (const unsigned seed : {1u, 2u, 3u}) meshes.push_back(randomTriangles(seed, 120));
  meshes.push_back(nearPlaneTriangles(4, 60));
  // Centred (s = 1/2 on the middle column, as a symmetric scene has it), turned and rolled, and
  // a plane nearly edge-on.
  for (const HorizonView& view :
       {HorizonView{1.0f, 0.0f, 0.0f, 0.0f, 0.0f}, HorizonView{2.5f, 31.0f, 17.0f, 0.13f, 0.0f},
        HorizonView{40.0f, 7.0f, -23.0f, 0.0f, 89.9f}})
    meshes.push_back(horizonPlane(view, viewport));
  for (const CrossingPlanes& view :
       {CrossingPlanes{0.5f, 3.0f, 20.0f, 1e-3f}, CrossingPlanes{2.0f, 40.0f, -35.0f, 1e-4f}})
    meshes.push_back(planesBehindTheCamera(view, viewport));
  meshes.push_back(groundUnderATriangleBehindTheCamera());
  return meshes;
}

// Counts what every combination misses of a readback of `mesh` (32F depth).
void compareCombinations(const DrawnProbe& drawn, std::vector<Combination>& combinations,
                         const reference::ResidentTexture& texture) {
  for (Combination& c : combinations)
    compareRaster(
        drawn.gl,
        oracleFrame(drawn.mesh, texture, drawn.viewport, c.arithmetic, DepthFormat::kDepth32F),
        c.counts);
}

// Draws each mesh on the implementation and counts what every combination misses of it; returns
// the meshes with their readbacks.
std::vector<DrawnProbe> drawAndCompare(const std::vector<ClipSpaceMesh>& meshes,
                                       std::vector<Combination>& combinations,
                                       const reference::ResidentTexture& texture,
                                       Viewport viewport) {
  std::vector<DrawnProbe> drawn;
  for (const ClipSpaceMesh& mesh : meshes) {
    drawn.push_back({mesh, viewport, drawTriangles(mesh, viewport)});
    compareCombinations(drawn.back(), combinations, texture);
  }
  return drawn;
}

// The combination taken: the first that reproduces everything, else the closest (fewest pixels
// of another triangle, then the attributes' and then the depth's distance in floats).
const Combination& closestCombination(const std::vector<Combination>& combinations) {
  const auto closer = [](const RasterCounts& a, const RasterCounts& b) {
    if (a.reproduces() != b.reproduces()) return a.reproduces();
    if (a.coverage != b.coverage) return a.coverage < b.coverage;
    if (a.attributeDistance != b.attributeDistance)
      return a.attributeDistance < b.attributeDistance;
    return a.depthDistance < b.depthDistance;
  };
  size_t taken = 0;
  for (size_t i = 1; i < combinations.size(); ++i)
    if (closer(combinations[i].counts, combinations[taken].counts)) taken = i;
  return combinations[taken];
}

// One family's evidence: per member, the fewest values any combination with it misses.
template <typename MemberOf, typename NameOf, typename Members>
ParameterFit familyFit(const char* parameter, const std::vector<Combination>& combinations,
                       const Combination& chosen, MemberOf memberOf, NameOf nameOfMember,
                       const Members& members) {
  const bool reproduced = chosen.counts.reproduces();
  ParameterFit fit;
  fit.parameter = parameter;
  fit.probe = kRasterProbe;
  fit.probes = chosen.counts.pixels;
  std::vector<std::string> reproducing;
  for (const auto& member : members) {
    uint64_t fewest = std::numeric_limits<uint64_t>::max();
    for (const Combination& c : combinations)
      if (memberOf(c.arithmetic) == member) {
        fewest = std::min(fewest, c.counts.total());
        if (c.counts.reproduces()) {
          const std::string name = nameOfMember(member);
          if (std::find(reproducing.begin(), reproducing.end(), name) == reproducing.end())
            reproducing.push_back(name);
        }
      }
    // A member no combination draws (snapped plane positions under scanline spans alone) has no
    // evidence to give.
    if (fewest != std::numeric_limits<uint64_t>::max())
      fit.members.push_back({nameOfMember(member), fewest});
  }
  fit.chosen = nameOfMember(memberOf(chosen.arithmetic));
  fit.consistent = reproducing;
  fit.pinned = reproduced;
  fit.mismatches = reproduced ? 0 : chosen.counts.total();
  if (!reproduced)
    fit.finding = "no combination of members reproduces every probe; closest " + fit.chosen + " (" +
                  fit.memberSummary() + kPixelsCounted +
                  "; the closest combination has the fewest pixels of another triangle, then its "
                  "coordinates and depth lie the fewest floats from the implementation's)";
  else if (reproducing.size() == 1)
    fit.finding = fit.chosen + ", bit for bit (" + fit.memberSummary() + kPixelsCounted + ")";
  else
    fit.finding = std::to_string(reproducing.size()) +
                  " members reproduce every probe, which cannot tell them apart; the first, " +
                  fit.chosen + ", is taken";
  return fit;
}

// The values of an EnumNames table, in its order.
template <typename Table>
auto valuesOf(const Table& table) {
  std::vector<std::remove_cvref_t<decltype(table[0].value)>> values;
  for (const auto& entry : table) values.push_back(entry.value);
  return values;
}

// The evidence of every family of the combined fit, with coverage alone's (subpixel_bits) after
// coverage's.
void addFamilyFits(RasterFits& result, const GridResult& grid,
                   const std::vector<Combination>& combinations, const Combination& chosen) {
  result.fits.push_back(familyFit(
      "coverage", combinations, chosen, [](const Arithmetic& a) { return a.coverage; },
      [](const Coverage& c) { return nameOf(c); }, grid.candidates));
  if (!result.coveragePinned) {
    result.fits.back().pinned = false;
    result.fits.back().fromGl45 = grid.coarsestBits == 0;
  }
  result.fits.push_back(grid.fit);
  result.fits.push_back(familyFit(
      "viewport", combinations, chosen, [](const Arithmetic& a) { return a.fusedViewport; },
      [](bool fused) { return std::string(fused ? "fused" : "unfused"); },
      std::vector<bool>{true, false}));
  result.fits.push_back(familyFit(
      "plane_setup", combinations, chosen, [](const Arithmetic& a) { return a.planeSetup; },
      [](PlaneSetup s) { return std::string(vt::nameOf(kPlaneSetupNames, s)); },
      valuesOf(kPlaneSetupNames)));
  result.fits.push_back(familyFit(
      "plane_positions", combinations, chosen, [](const Arithmetic& a) { return a.planePositions; },
      [](PlanePositions p) { return std::string(vt::nameOf(kPlanePositionsNames, p)); },
      valuesOf(kPlanePositionsNames)));
  result.fits.push_back(familyFit(
      "plane_evaluation", combinations, chosen,
      [](const Arithmetic& a) { return a.planeEvaluation; },
      [](PlaneEvaluation e) { return std::string(vt::nameOf(kPlaneEvaluationNames, e)); },
      valuesOf(kPlaneEvaluationNames)));
  result.fits.push_back(familyFit(
      "perspective", combinations, chosen, [](const Arithmetic& a) { return a.perspective; },
      [](Perspective p) { return std::string(vt::nameOf(kPerspectiveNames, p)); },
      valuesOf(kPerspectiveNames)));
  // Where the shader fit offered a measured reciprocal (shader_math_fit.h); `chosen` is one of
  // `combinations` (closestCombination).
  if (std::any_of(combinations.begin(), combinations.end(),
                  [](const Combination& c) { return c.arithmetic.reciprocal.table != nullptr; }))
    result.fits.push_back(familyFit(
        "perspective_reciprocal", combinations, chosen,
        [](const Arithmetic& a) { return a.reciprocal.table != nullptr; },
        [](bool measured) { return std::string(measured ? "measured" : "ieee"); },
        std::vector<bool>{false, true}));
  result.fits.push_back(familyFit(
      "depth_offset", combinations, chosen,
      [](const Arithmetic& a) { return a.depth.offsetAndClamp; },
      [](bool on) { return std::string(on ? "offset_and_clamp" : "as_interpolated"); },
      std::vector<bool>{true, false}));
}

// The residuals of a combination that does not reproduce everything, measured against the result
// sets of the model it leaves (render/result_set.h), which already allow what vertices moved
// within the sub-pixel grid explain: result.attributeUlps, unexplainedOwners, depthUlps and
// depthBeyondSets.
void boundResiduals(RasterFits& result, const Arithmetic& chosen, int gridBits,
                    const std::vector<DrawnProbe>& drawn,
                    const reference::ResidentTexture& texture) {
  PrecisionModel bounds = gl45Model();
  bounds.arithmetic = chosen;
  setCoverageBounds(bounds, result.coveragePinned, gridBits);
  bounds.attributeUlps = bounds.depthUlps = 0;
  // Attributes: the smallest bound, in the unit the result sets apply it (2^-23 of the terms
  // the plane evaluation sums, at least of the value: reference/result_set_builder.cpp), under
  // which every pixel's (s, t) lies in its alternative's interval. Measured in that unit, a
  // bound found on these probes carries over to other geometry; measured against the value
  // alone, it overstated what the horizon planes need by orders of magnitude.
  result.attributeUlps = smallestBound(
      [&](double ulps) {
        bounds.attributeUlps = ulps;
        return setResiduals(bounds, drawn, texture).attributesOutside == 0;
      },
      gl45Model().attributeUlps);
  bounds.attributeUlps = 0;
  SetResiduals r = setResiduals(bounds, drawn, texture);
  result.unexplainedOwners = r.unexplainedOwners;
  // A pixel whose triangle no set admits: the smallest whole depth bound that admits every one
  // (doubling up to gl45's, then halving the interval), or, past that, gl45's own.
  if (!r.unexplainedOwners) return;
  const double gl45 = gl45Model().depthUlps;
  const auto explains = [&](double ulps) {
    bounds.depthUlps = ulps;
    return setResiduals(bounds, drawn, texture).unexplainedOwners == 0;
  };
  if (!explains(gl45)) {
    // Not even gl45's bound admits them. The depth rule itself is probed on its own
    // (calibration.h, depth test); these pixels are where the oracle's sets are narrower
    // than the specification (a limit of the interval arithmetic of
    // reference/result_set_builder.cpp), so the bound stays gl45's and the finding says so.
    result.depthUlps = gl45;
    result.depthBeyondSets = true;
  } else {
    result.depthUlps = smallestBound(explains, gl45);
  }
}

// The attributes' evidence: the combination's mismatches and, beyond the grid, their bound.
ParameterFit attributesEvidence(const RasterCounts& c, const RasterFits& result) {
  ParameterFit attributes = {"attributes", kRasterProbe, c.shared};
  attributes.pinned = c.attributes == 0 && result.coveragePinned;
  attributes.mismatches = c.attributes;
  attributes.unit =
      "units of 2^-23 of the terms the plane evaluation sums, beyond the sub-pixel grid";
  attributes.largestResidual = result.attributeUlps;
  attributes.finding =
      c.attributes == 0
          ? "texture coordinates and fine derivatives bit for bit"
          : std::to_string(c.attributes) + " of " + std::to_string(c.shared) +
                " pixels' coordinates or derivatives differ; beyond what the sub-pixel grid "
                "explains, an error of " +
                std::to_string(result.attributeUlps) +
                " units of 2^-23 of the terms the plane evaluation sums admits them all";
  return attributes;
}

// The depth's evidence: the combination's mismatches, the pixels the grid does not explain and
// the depth bound that admits them.
ParameterFit depthEvidence(const RasterCounts& c, const RasterFits& result) {
  ParameterFit depth = {"depth", kRasterProbe, c.shared};
  depth.pinned = c.depth == 0 && result.coveragePinned;
  depth.mismatches = c.depth;
  depth.unit = "units of 2^-23 of the depth range or of the terms its evaluation sums, the larger";
  depth.largestResidual = result.depthUlps;
  depth.finding =
      c.depth == 0 ? "the stored 32F depth bit for bit"
      : result.unexplainedOwners == 0
          ? std::to_string(c.depth) + " of " + std::to_string(c.shared) +
                " pixels' depth differs; every pixel's triangle is one the sub-pixel grid "
                "allows"
          : std::to_string(c.depth) + " of " + std::to_string(c.shared) +
                " pixels' depth differs, and " + std::to_string(result.unexplainedOwners) +
                " pixels show a triangle the sub-pixel grid alone does not allow; " +
                (result.depthBeyondSets
                     ? std::string("no depth bound up to gl45's admits them in the oracle's "
                                   "result sets (whose depth intervals are narrower than the "
                                   "specification there): gl45's bound is kept")
                     : "a depth error of " + std::to_string(result.depthUlps) +
                           " units of 2^-23 of the depth range or of the terms its evaluation "
                           "sums, the larger, admits them all");
  return depth;
}

// Z24 under the members taken: sets result.arithmetic's conversion and z24Pinned; returns the
// family's evidence. From 120 random triangles, which show the conversion only where the
// combination reproduced every other probe; from the plane group's constant-depth squares where
// the folder holds them, whose window depth every member computes exactly (compared wherever the
// implementation drew the oracle's square); and from the pack's gl_FragDepth sweeps where the
// folder holds them: every float of [0.5, 1) and of [2^-8, 2^-7) written as the depth
// (probes/function_sweeps.h). Where the sweeps were drawn, the finding also counts how many of
// their values the exact product z (2^24 - 1), rounded to nearest, misses: a conversion no member
// states yet, which the next GPU's sweeps decide.
ParameterFit fitZ24(RasterFits& result, bool reproduced, const DrawnProbe& random,
                    const std::optional<DrawnProbe>& squares,
                    const reference::ResidentTexture& texture) {
  ParameterFit z24;
  z24.parameter = "z24";
  const bool randomCounts = !squares || reproduced;
  z24.probe = !squares ? "120 random triangles drawn into a Z24 depth buffer"
              : reproduced
                  ? "4,096 squares of constant depth and 120 random triangles drawn into a Z24 "
                    "depth buffer"
                  : "4,096 squares of constant depth drawn into a Z24 depth buffer";
  struct Written {
    uint32_t first;
    std::vector<uint32_t> stored;
  };
  std::vector<Written> written;
  for (const char* name : {"frag_depth", "frag_depth_low"}) {
    const FunctionSweep& sweep = *packSweep(name);
    if (std::optional<std::vector<uint32_t>> stored = functionSweep(sweep))
      written.push_back({sweep.first, std::move(*stored)});
  }
  if (!written.empty())
    z24.probe += "; gl_FragDepth of every float of [0.5, 1) and of [2^-8, 2^-7) into Z24";
  const auto sweptMisses = [&](auto&& expected) {
    uint64_t missed = 0;
    for (const Written& w : written)
      for (uint32_t i = 0; i < w.stored.size(); ++i)
        missed += w.stored[i] != expected(std::bit_cast<float>(w.first + i));
    return missed;
  };
  uint64_t sweptValues = 0;
  for (const Written& w : written) sweptValues += w.stored.size();
  for (const auto& [conversion, name] : kZ24ConversionNames) {
    Arithmetic a = result.arithmetic;
    a.depth.z24 = conversion;
    uint64_t missed = 0, shared = 0;
    const auto compare = [&](const DrawnProbe& drawn) {
      const Frame oracle =
          oracleFrame(drawn.mesh, texture, drawn.viewport, a, DepthFormat::kDepth24);
      const RasterReadback& gl = drawn.gl;
      for (size_t i = 0; i < oracle.triangle.size(); ++i) {
        if (gl.triangle[i] != oracle.triangle[i] || gl.triangle[i] < 0) continue;
        ++shared;
        missed += !sameBits(gl.depth[i], oracle.depth[i]);
      }
    };
    if (randomCounts) compare(random);
    if (squares) compare(*squares);
    const Z24Conversion member = conversion;  // a structured binding: no lambda captures it
    missed += sweptMisses([&](float z) { return reference::z24Of(z, member); });
    z24.probes = shared + sweptValues;
    z24.members.push_back({std::string(name), missed});
  }
  result.arithmetic.depth.z24 = kZ24ConversionNames[z24.choose()].value;
  result.z24Pinned =
      z24.pinned && (squares || !written.empty() || (result.coveragePinned && reproduced));
  z24.pinned = result.z24Pinned;
  z24.finding = (z24.pinned ? z24.chosen + ", bit for bit"
                            : std::string("not pinned: either of the two nearest values")) +
                " (" + z24.memberSummary() + " depths)";
  if (!written.empty()) {
    // Exact in double: a 24-bit mantissa times 2^24 - 1 needs at most 48 bits.
    const uint64_t exact = sweptMisses([](float z) {
      return static_cast<uint32_t>(std::nearbyint(static_cast<double>(z) * 16777215.0));
    });
    z24.finding += "; on the gl_FragDepth sweeps the exact product z (2^24 - 1) rounded to "
                   "nearest: " +
                   differ(exact, sweptValues);
  }
  return z24;
}

// The plane group (plane_probes.h), drawn where the folder holds it: its 32F draws join the
// combinations' counts and `drawn`; returns the Z24 squares and the shift evidence.
struct PlaneGroup {
  DrawnProbe squares;
  ShiftEvidence shifts;
};
std::optional<PlaneGroup> drawPlaneGroup(std::vector<Combination>& combinations,
                                         std::vector<DrawnProbe>& drawn,
                                         const reference::ResidentTexture& texture) {
  const std::vector<PlaneProbe> probes = planeProbes();
  if (!holdsOptionalGroup(probes.size())) return std::nullopt;
  std::vector<RasterReadback> readbacks;
  std::optional<DrawnProbe> squares;
  for (const PlaneProbe& probe : probes) {
    readbacks.push_back(drawTriangles(probe.mesh, probe.viewport, probe.format));
    DrawnProbe d{probe.mesh, probe.viewport, readbacks.back()};
    if (probe.format == DepthFormat::kDepth24) {
      squares = std::move(d);
      continue;
    }
    compareCombinations(d, combinations, texture);
    drawn.push_back(std::move(d));
  }
  return PlaneGroup{std::move(*squares), shiftEvidence(probes, readbacks)};
}

}  // namespace

RasterFits fitRasterization(const Arithmetic& base) {
  RasterFits result;
  const GridResult grid = fitGrid();
  result.subpixelBits = grid.coarsestBits;

  const ProbeTexture probeTexture(4);
  const reference::ResidentTexture& texture = probeTexture.texture();
  const Viewport viewport{160, 120};
  std::vector<Combination> combinations = allCombinations(base, grid.candidates);
  std::vector<DrawnProbe> drawn =
      drawAndCompare(rasterProbeMeshes(viewport), combinations, texture, viewport);
  const ClipSpaceMesh z24Mesh = randomTriangles(5, 120);
  const DrawnProbe z24Drawn{z24Mesh, viewport,
                            drawTriangles(z24Mesh, viewport, DepthFormat::kDepth24)};
  const std::optional<PlaneGroup> group = drawPlaneGroup(combinations, drawn, texture);

  const Combination& chosen = closestCombination(combinations);
  const bool reproduced = chosen.counts.reproduces();
  result.arithmetic = chosen.arithmetic;
  result.coveragePinned = chosen.counts.coverage == 0;
  addFamilyFits(result, grid, combinations, chosen);

  // The residuals of the combination taken: none when it reproduces everything.
  if (!reproduced) boundResiduals(result, chosen.arithmetic, grid.coarsestBits, drawn, texture);
  result.attributes = attributesEvidence(chosen.counts, result);
  result.depth = depthEvidence(chosen.counts, result);
  if (group) {
    for (ParameterFit* fit : {&result.attributes, &result.depth}) fit->probe += kPlaneGroupProbe;
    for (ParameterFit& fit : result.fits) {
      if (fit.probe == kRasterProbe) fit.probe += kPlaneGroupProbe;
      if (fit.parameter == "plane_evaluation") fit.finding += "; " + shiftFinding(group->shifts);
    }
  }
  result.fits.push_back(fitZ24(result, reproduced, z24Drawn,
                               group ? std::optional<DrawnProbe>(group->squares) : std::nullopt,
                               texture));
  return result;
}

void setCoverageBounds(PrecisionModel& m, bool coveragePinned, int gridBits) {
  if (coveragePinned) {
    m.subpixelBits = m.arithmetic.coverage.subpixelBits;
    m.fillRulePinned = true;
  } else if (gridBits > 0) {
    // Coverage is not the oracle's, but vertices move at most 2^-bits pixel: the result sets'
    // corner boxes shrink from gl45's 2^-4 to that; ties stay free.
    m.subpixelBits = gridBits;
  }
}

std::string rasterMemberOf(const std::string& family, const Arithmetic& a) {
  if (family == "coverage") return nameOf(a.coverage);
  if (family == "viewport") return a.fusedViewport ? "fused" : "unfused";
  if (family == "plane_setup") return std::string(vt::nameOf(kPlaneSetupNames, a.planeSetup));
  if (family == "plane_positions")
    return std::string(vt::nameOf(kPlanePositionsNames, a.planePositions));
  if (family == "plane_evaluation")
    return std::string(vt::nameOf(kPlaneEvaluationNames, a.planeEvaluation));
  if (family == "perspective") return std::string(vt::nameOf(kPerspectiveNames, a.perspective));
  if (family == "perspective_reciprocal") return a.reciprocal.table ? "measured" : "ieee";
  if (family == "depth_offset")
    return a.depth.offsetAndClamp ? "offset_and_clamp" : "as_interpolated";
  if (family == "z24") return std::string(vt::nameOf(kZ24ConversionNames, a.depth.z24));
  return "";
}

}  // namespace vt::calibrate
