#pragma once
// An evaluation's results as files in one folder (docs/design.md section 5: CSV, SVG and PNG plots
// and a short table, every error next to its run time):
//   frames.csv          per configuration and frame: the runtime's statistics, RMSE, SSIM, WSSIM
//   summary.md          per configuration: mean and minimum SSIM, mean WSSIM and RMSE, pages
//                       streamed and evicted, misses and run time; then mean SSIM per named
//                       motion, and the figures
//   summary.json        the same, with each configuration's settings, and the figures to draw
//                       ({"stem", "title", "measure", "runs"}), for scripts
//   ssim, wssim, rmse (.svg and .png)   the measure over the frames, one curve per configuration,
//                       the path's named motions shaded (the thesis's figures); and the
//                       description's figures of chosen runs, named by their file's stem
// The plots are drawn last, by the embedded scripts/evaluation-plots.py (eval/evaluation_plots.h);
// when they cannot be drawn the evaluation fails and no output folder is left.
// frames.csv holds the same bytes for any number of jobs; run times live in the summaries only.
// Every file is written to a temporary name and renamed.

#include <filesystem>
#include <string>
#include <vector>

#include "common/shard.h"
#include "eval/evaluation.h"

namespace vt {

// A figure of chosen runs (a claim of chapter 4 compares a few configurations, not all of them).
struct EvaluationFigure {
  std::string file;  // e.g. "basic5.png": its stem names basic5.svg and basic5.png
  std::string title;
  std::string measure = "ssim";   // ssim, wssim or rmse
  std::vector<std::string> runs;  // configuration labels, in the legend's order
};

struct EvaluationDescription {
  std::string title;           // e.g. "q3dm6ish: basic heuristics"
  std::string scene, texture;  // what was flown, for the record
  unsigned jobs = 1;
  std::vector<EvaluationFigure> figures;  // drawn besides the three plots of every run
  std::string referenceTexture;           // the references' texture, when not the flown one
};

// The part of an evaluation one shard flew (`vt eval --shard I/N`, common/shard.h: the
// configurations taken in turn): every configuration of the job, and which of them its runs are.
struct EvaluationPart {
  Shard shard;
  std::vector<FlightConfiguration> all;
  std::vector<size_t> runIndices;  // of the evaluation's runs in `all`, in order
};

// With `part`, the runs carry their indices among all configurations (frames.csv, summary.json),
// the figures name every configuration, and shard.json is written besides for mergeEvaluations.
void writeEvaluation(const std::filesystem::path& folder, const EvaluationDescription& description,
                     const CameraPath& path, const RenderSettings& settings,
                     const Evaluation& evaluation, const EvaluationPart* part = nullptr);

bool isEvaluationShard(const ShardFile& shard);

// The shards of one evaluation (requireCompleteJob's, in order) joined into `output`: frames.csv
// and the runs of summary.json as one run writes them, summary.md and the plots drawn from them.
// What the shards measured stays theirs: the runs' times, and for the whole the longest shard's
// wall and view times and the sum of the recolouring. Throws InputError naming a shard's file
// when its summary or frames do not hold its runs.
void mergeEvaluations(const std::vector<ShardFile>& shards, const std::filesystem::path& output);

}  // namespace vt
