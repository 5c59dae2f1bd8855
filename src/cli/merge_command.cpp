// vt merge SHARD... -o OUTPUT: the folders written by the shards of one job (`--shard I/N` of
// `vt crosscheck --captures`, `vt golden check` or `vt eval`) joined into the folder one run
// writes (workflows/merge_shards.h). Exits 1 when the merged verdict fails, as the job would.

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "workflows/merge_shards.h"

namespace vt {

void addMergeCommand(CLI::App& app) {
  struct Options {
    std::vector<std::string> shards;
    std::string output;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "merge",
      "Join the output folders of a job's shards (--shard I/N) into the one a single "
      "run writes");
  command
      ->add_option("SHARD", o->shards,
                   "The shards' output folders (each with shard.json), every shard of the job once")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("-o,--output", o->output, "Folder for the merged output")->required();
  command->callback([o] {
    std::vector<std::filesystem::path> folders(o->shards.begin(), o->shards.end());
    requireOutputFolder(o->output, folders);
    const std::string merged = mergeShards(folders, o->output);
    std::cout << "merged " << folders.size() << " shards of vt " << merged << " into " << o->output
              << "\n";
  });
}

}  // namespace vt
