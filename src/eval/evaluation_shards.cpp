// An evaluation's shards (`vt eval --shard I/N`): the record each writes and their merge
// (eval/evaluation_report.h, eval/evaluation_files.h).

#include <algorithm>
#include <sstream>

#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "eval/evaluation_files.h"
#include "eval/evaluation_report.h"

namespace vt {
namespace {

constexpr const char* kEvalShardCommand = "eval";

// What each shard measured for itself: not part of the job's identity.
constexpr std::array<const char*, 5> kMeasured = {"view_seconds", "recolor_seconds", "wall_seconds",
                                                  "reference_seconds", "jobs"};

// A run's index among the job's configurations, checked to be one of `shard`'s runs.
size_t ownIndex(const ShardFile& shard, const nlohmann::json& index, const std::string& what) {
  const auto k = index.get<size_t>();
  if (k >= shard.items.size() || !shard.shard.holdsInTurn(k))
    throw InputError(shard.file, what + " names run " + std::to_string(k) + ", which shard " +
                                     shard.shard.text() + " does not fly");
  return k;
}

// One shard's runs of summary.json and rows of frames.csv, put in their places.
struct MergedParts {
  nlohmann::json summary;  // the first shard's, whose runs and times are replaced
  std::string header;
  std::vector<nlohmann::json> runs;
  std::vector<std::string> rows;
  double viewSeconds = 0, wallSeconds = 0, referenceSeconds = 0, recolorSeconds = 0;
};

void addShard(const ShardFile& shard, MergedParts& merged) {
  const std::filesystem::path folder = shard.file.parent_path();
  const nlohmann::json summary = readJsonFile(folder / "summary.json", "shard's summary");
  const std::string csv = readTextFile(folder / "frames.csv", "the shard's frames");
  if (merged.summary.is_null()) merged.summary = summary;
  size_t own = 0;
  for (const nlohmann::json& run : summary.at("runs")) {
    merged.runs[ownIndex(shard, run.at("index"), "summary.json")] = run;
    ++own;
  }
  if (own != shard.records.size())
    throw InputError(folder / "summary.json", "holds " + std::to_string(own) + " runs, " +
                                                  shard.file.string() + " " +
                                                  std::to_string(shard.records.size()));
  std::istringstream lines(csv);
  std::string line, header;
  std::getline(lines, header);
  if (merged.header.empty()) merged.header = header;
  if (header != merged.header)
    throw InputError(folder / "frames.csv", "its columns are not the first shard's");
  while (std::getline(lines, line)) {
    const size_t comma = line.find(',');
    const std::string index = line.substr(0, comma);
    if (comma == std::string::npos || index.empty() ||
        !std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
        index.size() > 9)
      throw InputError(folder / "frames.csv", "a row without its configuration's index");
    merged.rows[ownIndex(shard, std::stoul(index), "frames.csv")].append(line).append("\n");
  }
  merged.viewSeconds = std::max(merged.viewSeconds, summary.at("view_seconds").get<double>());
  merged.wallSeconds = std::max(merged.wallSeconds, summary.at("wall_seconds").get<double>());
  merged.referenceSeconds =
      std::max(merged.referenceSeconds, summary.value("reference_seconds", 0.0));
  merged.recolorSeconds += summary.at("recolor_seconds").get<double>();
}

}  // namespace

ShardFile evaluationShard(const EvaluationPart& part, const nlohmann::json& summary) {
  ShardFile record{{}, kEvalShardCommand, part.shard, summary, {}, nlohmann::json::array()};
  record.inputs.erase("runs");
  for (const char* measured : kMeasured) record.inputs.erase(measured);
  record.inputs["configurations"] = nlohmann::json::array();
  for (const FlightConfiguration& c : part.all) {
    record.inputs["configurations"].push_back(c.toJson());
    record.items.push_back(c.label());
  }
  for (const size_t k : part.runIndices)
    record.records.push_back({{"item", record.items[k]}, {"index", k}});
  return record;
}

bool isEvaluationShard(const ShardFile& shard) { return shard.command == kEvalShardCommand; }

void mergeEvaluations(const std::vector<ShardFile>& shards, const std::filesystem::path& output) {
  MergedParts merged;
  const size_t runs = shards.front().items.size();
  merged.runs.resize(runs);
  merged.rows.resize(runs);
  for (const ShardFile& shard : shards) {
    try {
      addShard(shard, merged);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(shard.file.parent_path() / "summary.json",
                       "malformed summary of a shard: " + jsonErrorText(e));
    }
  }
  std::string csv = merged.header + "\n";
  for (size_t k = 0; k < runs; ++k) {
    if (merged.runs[k].is_null())
      throw InputError(shards[k % shards.size()].file,
                       "its summary.json holds no run of " + shards.front().items[k]);
    csv += merged.rows[k];
  }
  nlohmann::json& summary = merged.summary;
  summary["runs"] = merged.runs;
  summary["view_seconds"] = merged.viewSeconds;
  summary["wall_seconds"] = merged.wallSeconds;
  summary["recolor_seconds"] = merged.recolorSeconds;
  if (summary.contains("reference_seconds")) summary["reference_seconds"] = merged.referenceSeconds;
  try {
    writeEvaluationFiles(output, csv, summary, nullptr);
  } catch (const nlohmann::json::exception& e) {
    // A field summary.md needs is missing or mistyped in a shard's summary (nothing is written).
    throw InputError(shards.front().file.parent_path() / "summary.json",
                     "malformed summary of a shard: " + jsonErrorText(e));
  }
}

}  // namespace vt
