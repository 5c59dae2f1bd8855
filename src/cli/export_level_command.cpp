// vt export-level FILE --level M --output IMAGE: one level of a virtual texture as an image.

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "common/image_file.h"
#include "common/output_path.h"
#include "format/level_image.h"

namespace vt {

void addExportLevelCommand(CLI::App& app) {
  struct Options {
    std::string file;
    uint32_t level = 0;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "export-level", "Write one level of a virtual texture (page interiors) as an image");
  command->add_option("FILE", options->file, "Virtual-texture file (.vt)")->required();
  command->add_option("--level", options->level, "Level, 0 the coarsest")->required();
  command->add_option("-o,--output", options->output, "Image to write (.png, .tif, .exr, ...)")
      ->required();
  command->callback([options] {
    requireOutputFile(options->output, {options->file});
    const VirtualTextureReader reader(options->file);
    const LevelImage image = assembleLevel(reader, options->level);
    writeImage8(options->output, image.side, image.side, image.channels, image.texels);
    std::cout << "wrote " << options->output << " (" << image.side << " x " << image.side
              << " texels, level " << options->level << ")\n";
  });
}

}  // namespace vt
