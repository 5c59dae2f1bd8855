// vt info FILE [--json] [--verify] [--against OTHER]: what a virtual-texture file holds, after
// validating it; with --against, its error against another texture of the same pages, level by
// level (eval/level_comparison.h).

#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "eval/level_comparison.h"
#include "format/texture_report.h"

namespace vt {

void addInfoCommand(CLI::App& app) {
  struct Options {
    std::string file, against;
    bool json = false;
    bool verify = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "info", "Validate a virtual-texture file and print its levels, pages and NoiseValues");
  command->add_option("FILE", options->file, "Virtual-texture file (.vt)")->required();
  command->add_flag("--json", options->json, "Print the report as JSON");
  command->add_flag("--verify", options->verify, "Also read every page and check its checksum");
  command
      ->add_option("--against", options->against,
                   "Compare every page with this texture of the same pages (e.g. the uncompressed "
                   "one): mean SSIM, RMSE and PSNR per level")
      ->check(CLI::ExistingFile);
  command->callback([options] {
    const VirtualTextureReader reader(options->file);
    nlohmann::json report = textureReport(reader);
    if (options->verify) report["verified_pages"] = verifyAllPages(reader);
    if (options->against.empty()) {
      std::cout << (options->json ? report.dump(2) + "\n" : formatTextureReport(report));
      return;
    }
    const VirtualTextureReader other(options->against);
    const std::vector<LevelComparison> levels = compareLevels(reader, other);
    report["against"] = levelComparisonJson(other, levels);
    if (options->json) {
      std::cout << report.dump(2) << "\n";
      return;
    }
    std::cout << formatTextureReport(report) << "against      " << options->against << "\n"
              << "level    pages  mean SSIM      RMSE   PSNR (dB)\n";
    for (const LevelComparison& l : levels) {
      char line[96];
      std::snprintf(line, sizeof line, "%5u %8llu %10.6f %9.4f %11.3f\n", l.level,
                    static_cast<unsigned long long>(l.pages), l.meanSsim, l.rmse, l.psnrDb);
      std::cout << line;
    }
  });
}

}  // namespace vt
