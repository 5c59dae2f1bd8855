// vt crosscheck TEXTURE: named scenes, or frames of a flythrough of an OBJ scene, drawn by the
// oracle and by OpenGL and compared pixel by pixel (verify/crosscheck_scenes.h); vt crosscheck
// --captures DIR: another renderer's captures compared with the oracle
// (verify/crosscheck_captures.h). Exits 1 when any pixel is unexplained.

#include <filesystem>
#include <memory>
#include <optional>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "scene/test_scenes.h"
#include "workflows/crosscheck_to_folder.h"

namespace vt {

void addCrosscheckCommand(CLI::App& app) {
  struct Options {
    std::string texture, scenes = "all", size = "320x200", profile = "auto", output = "crosscheck";
    std::string mesh, path, captures, shard;
    int every = 8;
    unsigned threads = 0;
    bool allSets = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "crosscheck",
      "Render scenes with the oracle and with OpenGL, or read captures of any renderer, and "
      "compare them pixel by pixel");
  command->add_option("TEXTURE", o->texture, "Virtual-texture file (.vt); not with --captures");
  command
      ->add_option("--captures", o->captures,
                   "Compare the captures of this folder (frames another renderer drew, "
                   "reference/validate-your-renderer.md) with the oracle; writes junit.xml too")
      ->check(CLI::ExistingDirectory);
  command
      ->add_option("--shard", o->shard,
                   "With --captures: judge only part I of N (the captures taken in turn) and "
                   "write shard.json for `vt merge`")
      ->check(shardArgument());
  command->add_option("--threads", o->threads, "With --captures: oracle threads (0: every core)")
      ->check(workerCount());
  std::string names;
  for (const std::string& name : testSceneNames())
    names.append(names.empty() ? "" : ", ").append(name);
  command->add_option("--scenes", o->scenes, "Comma-separated scene names, or all: " + names)
      ->capture_default_str();
  command->add_option("--mesh", o->mesh, "An OBJ scene flown through along --path instead")
      ->check(CLI::ExistingFile);
  command->add_option("--path", o->path, "Camera path (.json) for --mesh")
      ->check(CLI::ExistingFile);
  command->add_option("--every", o->every, "With --path: every n-th frame")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--size", o->size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  command
      ->add_option(
          "--model,--profile", o->profile,
          "Precision model the other renderer is judged under: exact, llvmpipe, softpipe, gl45, or "
          "a model file (.json); auto: with --captures the model file a capture names, else a "
          "measured model of its renderer, else the shipped model its fingerprint names; for "
          "scenes a measured or shipped model whose fingerprint reproduces here; gl45 otherwise")
      ->capture_default_str();
  command->add_flag(
      "--all-sets", o->allSets,
      "Under a model with free parameters, build every pixel's result set, not only those where "
      "the other frame differs: the ambiguous fraction and set widths of whole frames, slower");
  command->add_option("-o,--output", o->output, "Folder for summary.json and difference images")
      ->capture_default_str();
  command->callback([o] {
    requireOutputFolder(o->output, {o->texture, o->captures, o->mesh, o->path});
    TemporaryFolder::requireReplaceable(o->output, "summary.json");
    if (!o->captures.empty() && !o->texture.empty())
      throw CLI::ValidationError("TEXTURE", "--captures takes none: each capture names its own");
    if (o->captures.empty() && o->texture.empty())
      throw CLI::ValidationError("TEXTURE", "needed without --captures");
    if (o->captures.empty() && !o->shard.empty())
      throw CLI::ValidationError("--shard", "shards split captures: needs --captures");
    if (o->captures.empty() && (o->mesh.empty() != o->path.empty()))
      throw CLI::ValidationError("--mesh/--path", "a flythrough needs both");
    crosscheckToFolder({.captures = o->captures,
                        .texture = o->texture,
                        .scenes = o->scenes,
                        .mesh = o->mesh,
                        .path = o->path,
                        .every = o->every,
                        .viewport = parseSize(o->size),
                        .model = o->profile,
                        .threads = o->threads,
                        .allSets = o->allSets,
                        .shard = parseShardOption(o->shard),
                        .output = o->output});
  });
}

}  // namespace vt
