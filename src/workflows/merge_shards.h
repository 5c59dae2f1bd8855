#pragma once
// `vt merge`'s work as one call: the folders the shards of one job wrote (`--shard I/N`,
// common/shard.h) joined into the folder one run of the whole job writes, byte for byte but for
// the times the shards measured. The command is the shards' own: `vt crosscheck --captures`,
// `vt golden check` or `vt eval`. InputError naming a shard's file when the shards are not one
// whole job; InputError naming the output's report when the merged verdict fails, as the one run's
// command would.

#include <filesystem>
#include <string>
#include <vector>

namespace vt {

// Returns the command the shards ran.
std::string mergeShards(const std::vector<std::filesystem::path>& shardFolders,
                        const std::filesystem::path& output);

}  // namespace vt
