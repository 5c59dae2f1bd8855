#pragma once
// Sharding (`--shard I/N`, docs/sharding.md): a command's work split into N parts by a rule that
// depends only on the order of its inputs (never on the machine, the time or the thread count),
// so that N jobs of a CI matrix or a Slurm array each do one part, and `vt merge` joins their
// folders into the bytes one run writes. Shards count from 1, as GitLab's CI_NODE_INDEX does.
//
// Each shard's folder holds what the command writes for its part and shard.json:
//   {"format": "vt-shard", "version": 1, "command": "crosscheck --captures", "shard": "2/4",
//    "inputs": {...what the whole job is, the same in every shard...},
//    "items": [...every item of the whole job, in order...],
//    "records": [...per item of this shard, what the merge needs...]}

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

inline constexpr uint32_t kMaxShards = 100000;

struct Shard {
  uint32_t index = 1, count = 1;  // 1 <= index <= count <= kMaxShards

  bool whole() const { return count == 1; }
  std::string text() const;  // "I/N"
  // Items taken in turn (item k, from 0, belongs to shard k mod N + 1): for independent items of
  // any cost (captures, configurations), whose neighbours tend to cost alike.
  bool holdsInTurn(size_t item) const;
  // Items taken as one contiguous block, [first, last), the blocks' sizes differing by at most
  // one: for items done in order (a flight's frames), so that a shard stops at its last.
  std::pair<size_t, size_t> block(size_t items) const;
  bool operator==(const Shard&) const = default;
};

// "I/N" with 1 <= I <= N <= kMaxShards; throws std::invalid_argument saying what is wrong.
Shard parseShard(std::string_view text);
// The same for a command-line option whose empty text means "no --shard": no shard.
std::optional<Shard> parseShardOption(std::string_view text);

// One shard's record, as written into and read from shard.json.
struct ShardFile {
  std::filesystem::path file;  // where it was read from (messages)
  std::string command;
  Shard shard;
  nlohmann::json inputs;
  std::vector<std::string> items;
  nlohmann::json records;  // an array
};

// Writes `folder`/shard.json atomically.
void writeShardFile(const std::filesystem::path& folder, const ShardFile& record);

// Reads `folder`/shard.json; throws InputError naming it when it is missing or malformed.
ShardFile readShardFile(const std::filesystem::path& folder);

// Copies the file `name` of `shard`'s folder into the folder `to`; throws InputError naming it,
// as `what` ("difference image"), when it is missing or not a regular file.
void copyShardFile(const ShardFile& shard, const std::string& name, const std::string& what,
                   const std::filesystem::path& to);

// The shards of one job, ordered by index: throws InputError naming a shard's file unless every
// shard ran the same command on the same inputs and items, and shards 1 to N are each there once.
std::vector<ShardFile> requireCompleteJob(std::vector<ShardFile> shards);

}  // namespace vt
