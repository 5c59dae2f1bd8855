#include "workflows/evaluate_to_folder.h"

#include <algorithm>
#include <thread>

#include "common/progress_bar.h"
#include "common/resource_limits.h"
#include "eval/evaluation.h"
#include "eval/flight_records.h"
#include "shader/needbuffer.h"

namespace vt {

Evaluation evaluateToFolder(const VirtualTextureReader& reader, EvaluateRequest request,
                            std::ostream& out) {
  std::optional<EvaluationPart> part;
  if (request.shard) {
    part = EvaluationPart{*request.shard, std::move(request.configurations), {}};
    request.configurations.clear();
    for (size_t k = 0; k < part->all.size(); ++k)
      if (part->shard.holdsInTurn(k)) {
        part->runIndices.push_back(k);
        request.configurations.push_back(part->all[k]);
      }
  }
  const std::vector<FlightConfiguration>& configurations = request.configurations;
  const CameraPath& path = request.path;
  const Viewport v = request.screen;
  requireEvaluationFits(request.configurationsFile.empty()
                            ? std::filesystem::path("the configurations")
                            : request.configurationsFile,
                        reader.description(), v, configurations);
  // The views drawn once, and one recolouring per configuration, along the path.
  requirePathPixelsFit(request.pathFile.empty() ? "the box room's path" : request.pathFile,
                       static_cast<uint64_t>(path.frameCount()), static_cast<uint64_t>(v.width),
                       static_cast<uint64_t>(v.height), 1 + configurations.size());
  EvaluationOptions options;
  options.settings.viewport = v;
  options.settings.need8 = need8Encodes(reader.description().finestLevel());
  options.settings.arithmetic = request.arithmetic;
  options.jobs = request.jobs;
  options.reference = request.reference;
  if (request.reference) requireSamePages(reader, *request.reference);
  const uint64_t total = static_cast<uint64_t>(path.frameCount()) * (1 + configurations.size());
  ProgressBar bar("eval", total);
  options.progress = [&bar](uint64_t done, uint64_t) { bar.update(done); };
  const Evaluation evaluation = evaluate(reader, request.mesh, path, configurations, options);

  request.description.jobs =
      request.jobs ? request.jobs : std::max(1u, std::thread::hardware_concurrency());
  writeEvaluation(request.output, request.description, path, options.settings, evaluation,
                  part ? &*part : nullptr);
  out << "evaluated " << configurations.size() << " configurations"
      << (part ? " (shard " + part->shard.text() + ")" : std::string()) << " over "
      << path.frameCount() << " frames in " << evaluation.wallSeconds << " s (views drawn once "
      << evaluation.viewSeconds << " s, shaded per run " << evaluation.recolorSeconds
      << " s); wrote " << (request.output / "summary.md").string() << "\n";
  for (const EvaluationRun& run : evaluation.runs) {
    const nlohmann::json totals = flightTotals(run.result);
    out << "  " << run.configuration.label() << ": mean SSIM " << totals["mean_ssim"].get<double>()
        << ", min SSIM " << totals["min_ssim"].get<double>() << ", mean RMSE "
        << totals["mean_rmse"].get<double>() << ", " << run.result.totals.streamed
        << " pages streamed, " << run.result.seconds << " s\n";
  }
  return evaluation;
}

}  // namespace vt
