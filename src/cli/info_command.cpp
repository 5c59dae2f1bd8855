// vt info FILE [--json] [--verify]: what a virtual-texture file holds, after validating it.

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "format/texture_report.h"

namespace vt {

void addInfoCommand(CLI::App& app) {
  struct Options {
    std::string file;
    bool json = false;
    bool verify = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "info", "Validate a virtual-texture file and print its levels, pages and NoiseValues");
  command->add_option("FILE", options->file, "Virtual-texture file (.vt)")->required();
  command->add_flag("--json", options->json, "Print the report as JSON");
  command->add_flag("--verify", options->verify, "Also read every page and check its checksum");
  command->callback([options] {
    const VirtualTextureReader reader(options->file);
    nlohmann::json report = textureReport(reader);
    if (options->verify) report["verified_pages"] = verifyAllPages(reader);
    std::cout << (options->json ? report.dump(2) + "\n" : formatTextureReport(report));
  });
}

}  // namespace vt
