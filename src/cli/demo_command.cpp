// vt demo [--output DIR]: the project's main job on its bundled default scene
// (workflows/demo.h).

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "common/output_path.h"
#include "workflows/demo.h"

namespace vt {

void addDemoCommand(CLI::App& app) {
  struct Options {
    std::string output = "out/demo";
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "demo", "Build the default scene's virtual texture, verify it and summarise it");
  command->add_option("-o,--output", options->output, "Output folder")->capture_default_str();
  command->callback([options] {
    requireOutputFolder(options->output, {});
    runDemo(options->output, std::cout);
  });
}

}  // namespace vt
