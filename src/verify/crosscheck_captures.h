#pragma once
// vt crosscheck --captures DIR: every capture of a folder (<vt/oracle/capture.h>), from any
// renderer, compared with the oracle under a precision profile.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "common/shard.h"
#include "verify/comparison_report.h"

namespace vt {

struct CapturesCheckOptions {
  std::filesystem::path captures;
  // Receives summary.json, junit.xml and per capture the colour difference and the pixel classes,
  // complete or not at all: written into a temporary folder that replaces `output` at the end.
  std::filesystem::path output;
  // exact, llvmpipe, softpipe, gl45 or a model file (.json) for every capture; or auto: per
  // capture, the model file it names, else a measured model of its renderer
  // ($VT_PRECISION_MODELS), else the shipped model for its renderer's name. The summary records
  // per capture the model, its file and which of these chose it ("model_from").
  std::string profile = "auto";
  unsigned threads = 0;  // the oracle's; 0: every core
  // Result sets for every pixel, not only where a capture differs: the ambiguous fraction and set
  // widths of whole frames (comparison_report.h), at the sets' full cost.
  bool allSets = false;
  // Given: judges only the captures this shard takes in turn (common/shard.h) and writes
  // shard.json besides, for mergeCapturesShards.
  std::optional<Shard> shard = std::nullopt;
};

struct CapturesCheck {
  ComparisonTotals totals;
  size_t captures = 0, unreadable = 0;
  bool passed() const { return totals.unexplained == 0 && unreadable == 0; }
};

// Prints one line per capture. A capture that cannot be read counts as unreadable and fails the
// check; a folder without captures throws oracle::Error before anything is written.
CapturesCheck crosscheckCaptures(const CapturesCheckOptions& options);

// Whether `shard` is a shard of `vt crosscheck --captures`.
bool isCapturesShard(const ShardFile& shard);

// The shards of one crosscheck (requireCompleteJob's, in order) joined into `output`: the
// summary.json, junit.xml and difference images one run writes, the cases' times those the shards
// measured. Throws InputError naming a shard's file when a record is missing or malformed.
CapturesCheck mergeCapturesShards(const std::vector<ShardFile>& shards,
                                  const std::filesystem::path& output);

}  // namespace vt
