#include "workflows/merge_shards.h"

#include <algorithm>

#include "common/error.h"
#include "common/shard.h"
#include "eval/evaluation_report.h"
#include "eval/golden_report.h"
#include "verify/crosscheck_captures.h"

namespace vt {

std::string mergeShards(const std::vector<std::filesystem::path>& shardFolders,
                        const std::filesystem::path& output) {
  std::vector<ShardFile> shards;
  for (const std::filesystem::path& folder : shardFolders) shards.push_back(readShardFile(folder));
  shards = requireCompleteJob(std::move(shards));
  const ShardFile& first = shards.front();
  if (isCapturesShard(first)) {
    if (!mergeCapturesShards(shards, output).passed())
      throw InputError(first.inputs.at("captures").get<std::string>(),
                       "crosscheck found unexplained pixels or unreadable captures (see " +
                           (output / "junit.xml").string() + ")");
    return first.command;
  }
  if (isGoldenCheckShard(first)) {
    const GoldenCheck check = mergeGoldenCheckShards(shards, output);
    if (!check.passed()) {
      const auto failed = std::count_if(check.frames.begin(), check.frames.end(),
                                        [](const GoldenFrameCheck& f) { return !f.passed; });
      throw InputError(first.inputs.at("golden").get<std::string>(),
                       std::to_string(failed) + " of " + std::to_string(check.frames.size()) +
                           " golden frames differ (see " + (output / "check.json").string() + ")");
    }
    return first.command;
  }
  if (isEvaluationShard(first)) {
    mergeEvaluations(shards, output);
    return first.command;
  }
  throw InputError(first.file, "shards of \"" + first.command + "\", which vt cannot merge");
}

}  // namespace vt
