// vt demo [--output DIR]: the project's main job on its bundled default scene. Today: generate the
// default scene's material images and layout, build its virtual texture with `vt build`'s
// builder, read it back, verify every page, print its summary and write one level as an image.

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include "build/demo_scene.h"
#include "build/texture_builder.h"
#include "cli/commands.h"
#include "cli/texture_report.h"
#include "common/image_file.h"
#include "format/level_image.h"

namespace vt {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  struct Options {
    std::string output = "out/demo";
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "demo", "Build the default scene's virtual texture, verify it and summarise it");
  command->add_option("-o,--output", options->output, "Output folder")->capture_default_str();
  command->callback([options] {
    const std::filesystem::path folder = options->output;
    auto start = std::chrono::steady_clock::now();
    const std::filesystem::path layoutFile = writeDemoScene(folder / "scene");
    std::cout << "wrote the default scene " << layoutFile.string() << " in " << secondsSince(start)
              << " s\n";

    const Layout layout = readLayout(layoutFile);
    const std::filesystem::path file = folder / "scene.vt";
    const BuildReport build = buildVirtualTexture(layout, file);
    std::cout << "built " << file.string() << " in " << build.seconds << " s\n";

    start = std::chrono::steady_clock::now();
    const VirtualTextureReader reader(file);
    nlohmann::json report = textureReport(reader);
    report["verified_pages"] = verifyAllPages(reader);
    std::cout << "read and verified in " << secondsSince(start) << " s\n\n"
              << formatTextureReport(report) << '\n';

    const uint32_t level = reader.description().finestLevel() - 1;
    const std::filesystem::path image = folder / ("level" + std::to_string(level) + ".png");
    const LevelImage pixels = assembleLevel(reader, level);
    writeImage8(image, pixels.side, pixels.side, pixels.channels, pixels.texels);
    std::cout << "wrote " << image.string() << " (level " << level << ", " << pixels.side << " x "
              << pixels.side << " texels)\n";
  });
}

}  // namespace vt
