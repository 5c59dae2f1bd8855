#include "eval/evaluation_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "common/posix_file.h"
#include "eval/evaluation_files.h"
#include "eval/evaluation_plots.h"
#include "eval/flight_records.h"
#include "render/arithmetic_points.h"

namespace vt {
namespace {

std::string fixed(double value, int digits) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

// Markdown table cells must not contain '|'.
std::string cell(std::string text) {
  for (char& c : text)
    if (c == '|') c = '/';
  return text;
}

// Run r's index among all configurations: r itself, or in a shard the part's.
size_t runIndex(const EvaluationPart* part, size_t r) { return part ? part->runIndices[r] : r; }

std::string framesCsv(const Evaluation& evaluation, const EvaluationPart* part) {
  std::string csv = flightCsvHeader(true, "configuration,");
  for (size_t r = 0; r < evaluation.runs.size(); ++r)
    csv += flightCsvRows(evaluation.runs[r].result, true, std::to_string(runIndex(part, r)) + ",");
  return csv;
}

// The figures the plotting script draws: SSIM, WSSIM and RMSE of every run, then the
// description's figures of chosen runs, each by the stem of its file name (basic5.png: basic5.svg
// and basic5.png).
nlohmann::json figuresJson(const EvaluationDescription& description, const Evaluation& evaluation,
                           const EvaluationPart* part) {
  std::vector<std::string> labels;
  if (part)
    for (const FlightConfiguration& c : part->all) labels.push_back(c.label());
  else
    for (const EvaluationRun& run : evaluation.runs) labels.push_back(run.configuration.label());
  nlohmann::json figures = nlohmann::json::array();
  for (const auto& [stem, measure, name] :
       {std::tuple{"ssim", "ssim", "SSIM"}, {"wssim", "wssim", "WSSIM"}, {"rmse", "rmse", "RMSE"}})
    figures.push_back({{"stem", stem},
                       {"title", description.title + ": " + name},
                       {"measure", measure},
                       {"runs", labels}});
  for (const EvaluationFigure& figure : description.figures) {
    for (const std::string& label : figure.runs)
      if (std::find(labels.begin(), labels.end(), label) == labels.end())
        throw std::invalid_argument("figure '" + figure.title + "': no configuration named '" +
                                    label + "'");
    figures.push_back({{"stem", std::filesystem::path(figure.file).stem().string()},
                       {"title", figure.title},
                       {"measure", figure.measure},
                       {"runs", figure.runs}});
  }
  return figures;
}

nlohmann::json summaryJson(const EvaluationDescription& description, const CameraPath& path,
                           const RenderSettings& settings, const Evaluation& evaluation,
                           const EvaluationPart* part) {
  nlohmann::json motions = nlohmann::json::array();
  for (const NamedMotion& m : path.motions())
    motions.push_back({{"name", m.name}, {"kind", m.kind}, {"first", m.first}, {"last", m.last}});
  nlohmann::json runs = nlohmann::json::array();
  for (size_t r = 0; r < evaluation.runs.size(); ++r) {
    const EvaluationRun& run = evaluation.runs[r];
    nlohmann::json perMotion = nlohmann::json::array();
    for (const NamedMotion& m : path.motions()) {
      const RangeQuality q = rangeQuality(run.result, m.first, m.last);
      perMotion.push_back({{"name", m.name},
                           {"mean_ssim", q.meanSsim},
                           {"min_ssim", q.minSsim},
                           {"mean_wssim", q.meanWssim},
                           {"mean_rmse", q.meanRmse}});
    }
    nlohmann::json entry = {{"index", runIndex(part, r)},
                            {"name", run.configuration.label()},
                            {"configuration", run.configuration.toJson()},
                            {"cache_side_frames", run.cacheSide},
                            {"seconds", run.result.seconds},
                            {"times", flightTimesJson(run.result.times)},
                            {"motions", perMotion}};
    entry.update(flightTotals(run.result));
    runs.push_back(entry);
  }
  nlohmann::json summary = {{"title", description.title},
                            {"scene", description.scene},
                            {"texture", description.texture},
                            {"frames", path.frameCount()},
                            {"width", settings.viewport.width},
                            {"height", settings.viewport.height},
                            {"profile", arithmeticLabel(settings.arithmetic)},
                            {"jobs", description.jobs},
                            {"view_seconds", evaluation.viewSeconds},
                            {"recolor_seconds", evaluation.recolorSeconds},
                            {"wall_seconds", evaluation.wallSeconds},
                            {"motions", motions},
                            {"runs", runs},
                            {"figures", figuresJson(description, evaluation, part)}};
  if (!evaluation.encoding.empty()) {
    // The encoding's own error: the flown texture with every page resident, frame by frame.
    nlohmann::json ssims = nlohmann::json::array(), wssims = nlohmann::json::array();
    double sum = 0.0, wsum = 0.0, least = 1.0;
    for (const SsimAndWssim& q : evaluation.encoding) {
      ssims.push_back(q.ssim);
      wssims.push_back(q.wssim);
      sum += q.ssim;
      wsum += q.wssim;
      least = std::min(least, q.ssim);
    }
    const auto n = static_cast<double>(evaluation.encoding.size());
    summary["reference_texture"] = description.referenceTexture;
    summary["reference_seconds"] = evaluation.referenceSeconds;
    summary["encoding"] = {{"mean_ssim", sum / n},
                           {"min_ssim", least},
                           {"mean_wssim", wsum / n},
                           {"ssim", ssims},
                           {"wssim", wssims}};
  }
  return summary;
}

}  // namespace

std::string summaryMarkdown(const nlohmann::json& summary) {
  std::ostringstream md;
  md << "# " << cell(summary["title"]) << "\n\n"
     << summary["frames"].get<int>() << " frames at " << summary["width"].get<int>() << " x "
     << summary["height"].get<int>() << ", scene `" << summary["scene"].get<std::string>()
     << "`, texture `" << summary["texture"].get<std::string>() << "`; quality against every "
     << "needed page resident"
     << (summary.contains("reference_texture")
             ? " of `" + summary["reference_texture"].get<std::string>() + "`"
             : std::string())
     << " (SSIM 8 x 8 on luminance, WSSIM, RMSE in 8-bit units). Run time: "
     << "the flight alone (drawing, analysis, streaming), " << summary["jobs"].get<unsigned>()
     << " threads; each view drawn once for every run (reference image and needbuffers) "
     << fixed(summary["view_seconds"].get<double>(), 1) << " s, shaded under every run's cache "
     << "state " << fixed(summary["recolor_seconds"].get<double>(), 1) << " s.\n\n"
     << "| Configuration | mean SSIM | min SSIM | mean WSSIM | mean RMSE | pages streamed | "
        "pages evicted | needed pages missed | run time (s) |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& run : summary["runs"])
    md << "| " << cell(run["name"]) << " | " << fixed(run["mean_ssim"], 4) << " | "
       << fixed(run["min_ssim"], 4) << " | " << fixed(run["mean_wssim"], 4) << " | "
       << fixed(run["mean_rmse"], 3) << " | " << run["streamed"].get<uint64_t>() << " | "
       << run["evicted"].get<uint64_t>() << " | " << run["misses"].get<uint64_t>() << " | "
       << fixed(run["seconds"], 2) << " |\n";
  if (summary.contains("encoding")) {
    const auto& e = summary["encoding"];
    md << "\nThe encoding alone (`" << summary["texture"].get<std::string>()
       << "` with every needed page resident against the reference): mean SSIM "
       << fixed(e["mean_ssim"], 4) << ", min SSIM " << fixed(e["min_ssim"], 4)
       << ", mean WSSIM " << fixed(e["mean_wssim"], 4) << "; its reference frames took "
       << fixed(summary["reference_seconds"].get<double>(), 1) << " s.\n";
  }
  if (!summary["motions"].empty()) {
    md << "\nMean SSIM per named motion (frames first to last):\n\n| Motion | frames |";
    for (const auto& run : summary["runs"]) md << ' ' << cell(run["name"]) << " |";
    md << "\n|---|---|";
    for (size_t r = 0; r < summary["runs"].size(); ++r) md << "---:|";
    md << '\n';
    for (size_t m = 0; m < summary["motions"].size(); ++m) {
      const auto& motion = summary["motions"][m];
      md << "| " << cell(motion["name"]) << " (" << motion["kind"].get<std::string>() << ") | "
         << motion["first"].get<int>() << "-" << motion["last"].get<int>() << " |";
      for (const auto& run : summary["runs"])
        md << ' ' << fixed(run["motions"][m]["mean_ssim"], 4) << " |";
      md << '\n';
    }
  }
  md << '\n';
  for (const auto& figure : summary["figures"])
    md << "![" << figure["title"].get<std::string>() << "](" << figure["stem"].get<std::string>()
       << ".svg)\n\n";
  return md.str();
}

void writeEvaluationFiles(const std::filesystem::path& destination, const std::string& csv,
                          const nlohmann::json& summary, const ShardFile* shard) {
  // Written whole into a temporary folder that then replaces `folder`: a previous evaluation
  // there stays complete until the new one is.
  TemporaryFolder staging(destination, "summary.json");
  const std::filesystem::path& folder = staging.path();
  writeFileAtomically(folder / "frames.csv", csv);
  writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
  writeFileAtomically(folder / "summary.md", summaryMarkdown(summary));
  if (shard)
    writeShardFile(folder, *shard);
  else
    // Last: the plots read the staged frames.csv and summary.json; a failure there leaves no
    // output folder.
    drawEvaluationPlots(folder, destination);
  staging.commit();
}

void writeEvaluation(const std::filesystem::path& destination,
                     const EvaluationDescription& description, const CameraPath& path,
                     const RenderSettings& settings, const Evaluation& evaluation,
                     const EvaluationPart* part) {
  const nlohmann::json summary = summaryJson(description, path, settings, evaluation, part);
  std::optional<ShardFile> shard;
  if (part) shard = evaluationShard(*part, summary);
  writeEvaluationFiles(destination, framesCsv(evaluation, part), summary,
                       shard ? &*shard : nullptr);
}

}  // namespace vt
