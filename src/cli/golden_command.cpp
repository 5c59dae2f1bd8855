// vt golden generate|check: golden images of a flight (eval/golden.h). `generate` records every
// n-th frame of a scene, path and configuration; `check` flies it again with the oracle or the GL
// path and exits 1 when a frame differs (exactly for the oracle and for GL under the llvmpipe
// profile, within the profile's colour bound otherwise).

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/error.h"
#include "common/output_path.h"
#include "eval/golden.h"
#include "render/arithmetic_points.h"
#include "workflows/check_golden_set.h"

namespace vt {
void addGoldenCommand(CLI::App& app) {
  CLI::App* golden = app.add_subcommand("golden", "Generate or check golden images of a flight");
  golden->require_subcommand(1);

  struct Generate {
    GoldenRequest request;
    std::string texture, mesh, path, size = "160x100", profile = "exact", output;
  };
  auto g = std::make_shared<Generate>();
  CLI::App* generate = golden->add_subcommand("generate", "Record every n-th frame of a flight");
  generate->add_option("TEXTURE", g->texture, "Virtual-texture file (.vt)")->required();
  generate->add_option("--mesh", g->mesh, "OBJ mesh with virtual texture coordinates")->required();
  generate->add_option("--path", g->path, "Camera path or storyboard (.json)")->required();
  auto configuration = std::make_shared<ConfigurationOptions>(generate);
  generate->add_option("--size", g->size, "WIDTHxHEIGHT")
      ->check(sizeValidator())
      ->capture_default_str();
  generate->add_option("--every", g->request.every, "Record every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  generate
      ->add_option("--profile", g->profile,
                   "The oracle's arithmetic: " + joinedArithmeticPointNames())
      ->check(CLI::IsMember(arithmeticPointNames()))
      ->capture_default_str();
  generate->add_option("-o,--output", g->output, "Golden folder")->required();
  generate->callback([g, configuration] {
    requireOutputFolder(g->output, {g->texture, g->mesh, g->path, configuration->file()});
    GoldenRequest request = g->request;
    request.texture = g->texture;
    request.mesh = g->mesh;
    request.path = g->path;
    request.viewport = parseSize(g->size);
    request.profile = arithmeticPoint(g->profile);
    request.configuration = configuration->configuration();
    generateGolden(request, g->output);
    std::cout << "wrote golden images of every " << request.every << "th frame to "
              << (std::filesystem::path(g->output) / "golden.json").string() << "\n";
  });

  struct Check {
    std::string golden, texture, mesh, path, backend = "oracle", model = "auto",
                                             output = "golden-check", shard;
  };
  auto c = std::make_shared<Check>();
  CLI::App* check = golden->add_subcommand("check", "Fly a golden set again and compare");
  check->add_option("GOLDEN", c->golden, "Golden folder (with golden.json)")->required();
  check->add_option("--texture", c->texture, "The virtual-texture file the goldens were made of")
      ->required();
  check->add_option("--mesh", c->mesh, "Their mesh")->required();
  check->add_option("--path", c->path, "Their camera path")->required();
  check->add_option("--backend", c->backend, "oracle or gl")
      ->check(CLI::IsMember({"oracle", "gl"}))
      ->capture_default_str();
  check
      ->add_option(
          "--model", c->model,
          "The precision model (exact, llvmpipe, softpipe, gl45 or a model file); auto: with "
          "--backend gl a measured or shipped model whose fingerprint reproduces here, else "
          "gl45; with the oracle the golden set's own profile")
      ->capture_default_str();
  check
      ->add_option("--shard", c->shard,
                   "Check only part I of N (a contiguous block of the recorded frames, flown up to "
                   "its last) and write shard.json for `vt merge`")
      ->check(shardArgument());
  check->add_option("-o,--output", c->output, "Folder for check.json and difference images")
      ->capture_default_str();
  check->callback([c] {
    requireOutputFolder(c->output, {c->golden, c->texture, c->mesh, c->path});
    checkGoldenSet({.golden = c->golden,
                    .texture = c->texture,
                    .mesh = c->mesh,
                    .path = c->path,
                    .backend = parseBackend(c->backend),
                    .model = c->model,
                    .output = c->output,
                    .shard = parseShardOption(c->shard)},
                   std::cout, std::cerr);
  });
}

}  // namespace vt
