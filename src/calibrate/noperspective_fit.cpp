#include "calibrate/noperspective_fit.h"

#include "calibrate/plane_probes.h"
#include "calibrate/probe_texture.h"
#include "calibrate/raster_fit.h"
#include "probes/probe_draws.h"

namespace vt::calibrate {

std::optional<ParameterFit> fitNoperspectivePlanes(const Arithmetic& chosen) {
  const std::vector<NoperspectiveProbe> probes = noperspectiveProbes();
  if (!holdsOptionalGroup(probes.size())) return std::nullopt;
  std::vector<RasterReadback> drawn;
  for (const NoperspectiveProbe& probe : probes)
    drawn.push_back(drawTriangles(probe.drawn, probe.viewport, DepthFormat::kDepth32F,
                                  Interpolation::kNoPerspective));

  const ProbeTexture probeTexture(4);
  ParameterFit fit;
  fit.parameter = "noperspective_planes";
  fit.probe =
      "400 small and 60 large triangles on the 1/256 grid with w of 0.5 to 4 at their vertices, "
      "noperspective coordinates, against the oracle's of the same triangles divided by w";
  fit.unit = "pixels";
  for (const auto& [setup, setupName] : kPlaneSetupNames)
    for (const auto& [positions, positionsName] : kPlanePositionsNames) {
      // Scanline spans snap no position to set planes up through.
      if (positions == PlanePositions::kSnapped &&
          chosen.coverage.rule != CoverageRule::kSnappedEdges)
        continue;
      for (const auto& [evaluation, evaluationName] : kPlaneEvaluationNames) {
        Arithmetic a = chosen;
        a.planeSetup = setup;
        a.planePositions = positions;
        a.planeEvaluation = evaluation;
        RasterCounts counts;
        for (size_t i = 0; i < probes.size(); ++i)
          compareRaster(drawn[i],
                        oracleFrame(probes[i].divided, probeTexture.texture(), probes[i].viewport,
                                    a, DepthFormat::kDepth32F),
                        counts);
        fit.probes = counts.pixels;
        fit.members.push_back({std::string(setupName) + "/" + std::string(positionsName) + "/" +
                                   std::string(evaluationName),
                               counts.differing});
      }
    }
  fit.choose();
  if (!fit.pinned) fit.largestResidual = static_cast<double>(fit.mismatches);
  fit.finding = (fit.pinned ? "reproduced bit for bit by plane setup/positions/evaluation " +
                                  fit.chosen
                            : "no member reproduces them; closest " + fit.chosen) +
                " (" + fit.memberSummary() + " pixels)";
  return fit;
}

}  // namespace vt::calibrate
