#pragma once
// A golden check's report (eval/golden.h): check.json, and for a shard of the check
// (`--shard I/N`, common/shard.h: one contiguous block of the recorded frames) shard.json, which
// mergeGoldenCheckShards joins into the check.json and difference images one run writes.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/shard.h"
#include "eval/golden.h"
#include "eval/golden_manifest.h"

namespace vt {

// check.json into `report`; `golden` is the golden folder as given.
void writeCheckReport(const std::filesystem::path& report, const std::filesystem::path& golden,
                      const GoldenCheck& check);

// The files a check was given, as given (they name the job in shard.json).
struct GoldenCheckFiles {
  std::filesystem::path golden, texture, mesh, path;
};

// shard.json into `report`: the job (files, backend, profile and model), every recorded frame of
// the golden set, and this shard's frame checks.
void writeGoldenCheckShard(const std::filesystem::path& report, const GoldenManifest& golden,
                           const GoldenCheckFiles& files, Shard shard, const GoldenCheck& check);

bool isGoldenCheckShard(const ShardFile& shard);

// The shards of one golden check (requireCompleteJob's, in order) joined into `output`. Throws
// InputError naming a shard's file when a frame's record is missing or malformed.
GoldenCheck mergeGoldenCheckShards(const std::vector<ShardFile>& shards,
                                   const std::filesystem::path& output);

}  // namespace vt
