#pragma once
// The files of an evaluation folder (eval/evaluation_report.h) from its summary and frames, for
// the report and for the merge of its shards (eval/evaluation_shards.cpp).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "common/shard.h"
#include "eval/evaluation_report.h"

namespace vt {

// summary.md of summary.json.
std::string summaryMarkdown(const nlohmann::json& summary);

// frames.csv, summary.json and summary.md into a temporary folder that replaces `destination`
// once complete; a shard's shard.json besides (and no plots: they are drawn once, merged);
// otherwise the plots.
void writeEvaluationFiles(const std::filesystem::path& destination, const std::string& csv,
                          const nlohmann::json& summary, const ShardFile* shard);

// A shard's record: the job (summary.json's fields but its runs and times, and every
// configuration), every configuration's label as the items, and per own run its index.
ShardFile evaluationShard(const EvaluationPart& part, const nlohmann::json& summary);

}  // namespace vt
