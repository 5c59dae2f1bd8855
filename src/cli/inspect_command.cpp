// vt inspect TEXTURE: a frame-by-frame debugging page of one flight (eval/inspect_page.h), for
// finding out why a configuration streamed what it streamed. Per frame: the rendered image, the
// reference (every needed page resident), their difference, the needbuffer by level, the level
// each needed page resolves to, the cache atlas, the statistics, the head of the priority queue
// with each page's heuristic terms, and the pages streamed for the next frame; with --against,
// a second configuration flown over the same path beside the first.

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/configuration_options.h"
#include "cli/size_argument.h"
#include "common/output_path.h"
#include "eval/configurations_file.h"
#include "workflows/inspect_to_page.h"

namespace vt {

void addInspectCommand(CLI::App& app) {
  struct Options {
    FlightSceneArguments scene;
    std::string output = "inspect.html";
    int first = 0, last = -1, every = 1, queue = 24, atlasSide = 512;
    std::string against, againstName;
  };
  auto o = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "inspect", "Write a self-contained HTML page to step through a flight frame by frame");
  o->scene.addTo(command);
  auto configurationOptions = std::make_shared<ConfigurationOptions>(command);
  command->add_option("--first", o->first, "First frame shown")->capture_default_str();
  command->add_option("--last", o->last, "Last frame shown (-1: the path's last)")
      ->capture_default_str();
  command->add_option("--every", o->every, "Show every n-th frame")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--queue", o->queue, "Entries of the priority queue shown per frame")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  command->add_option("--atlas-side", o->atlasSide, "Largest side of the cache atlas image")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  CLI::Option* against =
      command->add_option("--against", o->against,
                          "A configurations file (vt eval's --configs): fly its configuration "
                          "named by --against-name too and show the two side by side");
  CLI::Option* againstName =
      command->add_option("--against-name", o->againstName,
                          "The configuration of the --against file shown beside the first");
  against->needs(againstName);
  againstName->needs(against);
  command->add_option("-o,--output", o->output, "HTML file")->capture_default_str();
  command->callback([o, configurationOptions] {
    std::vector<std::filesystem::path> inputs = o->scene.inputs();
    inputs.push_back(configurationOptions->file());
    inputs.push_back(o->against);
    requireOutputFile(o->output, inputs);
    std::optional<FlightConfiguration> against;
    if (!o->against.empty()) against = loadNamedConfiguration(o->against, o->againstName);
    const VirtualTextureReader reader(o->scene.texture);
    inspectToPage(reader,
                  Inspection{.texture = o->scene.texture,
                             .sceneName = o->scene.sceneName(),
                             .pathFile = o->scene.path,
                             .mesh = o->scene.loadMesh(),
                             .path = o->scene.cameraPath(),
                             .configuration = configurationOptions->configuration(),
                             .against = against,
                             .screen = parseSize(o->scene.size),
                             .screenText = o->scene.size,
                             .first = o->first,
                             .last = o->last,
                             .every = o->every,
                             .queue = o->queue,
                             .atlasSide = o->atlasSide,
                             .output = o->output},
                  std::cout);
  });
}

}  // namespace vt
