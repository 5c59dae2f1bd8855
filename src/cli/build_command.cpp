// vt build INPUT -o OUTPUT: compile a layout (.json) or one image into a virtual-texture file.

#include <iostream>
#include <memory>

#include "build/texture_builder.h"
#include "cli/argument_checks.h"
#include "cli/commands.h"
#include "common/output_path.h"
#include "format/page_address.h"
#include "format/texture_description.h"
#include "workflows/build_texture.h"

namespace vt {

void addBuildCommand(CLI::App& app) {
  struct Options {
    std::string input, output;
    std::optional<uint32_t> pageSize, border, channels;
    std::optional<uint64_t> side;
    std::string colorSpace, filter, format;
    unsigned threads = 0;
    uint64_t keepFree = 0;
    bool ancestorErrors = false, quiet = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "build", "Compile a layout of images (.json) or one image into a virtual-texture file");
  command->add_option("INPUT", options->input, "Layout file (.json) or an image")->required();
  command->add_option("-o,--output", options->output, "Virtual-texture file to write")->required();
  command->add_option("--page-size", options->pageSize, "Page size P, a power of two (128)")
      ->check(pageSizeArgument());
  command->add_option("--border", options->border, "Border B in texels, B < P (4)")
      ->check(CLI::Range(0u, kMaxPageSize - 1));
  command
      ->add_option("--side", options->side,
                   "Finest level side, P * 2^L (the smallest that holds the images)")
      ->check(textureSideArgument());
  command->add_option("--channels", options->channels, "Channels 1..4 (the images' most)")
      ->check(CLI::Range(1u, kMaxChannels));
  command
      ->add_option("--color-space", options->colorSpace,
                   "srgb: filter colour in linear light (default); linear: as stored")
      ->check(CLI::IsMember(namesOf(kColorSpaceNames)));
  command->add_option("--filter", options->filter, "Mip filter: box (default) or tent")
      ->check(CLI::IsMember(namesOf(kMipFilterNames)));
  command
      ->add_option("--format", options->format,
                   "Stored pages: rgba8 (default), bc1 (opaque colour, 8:1 against RGBA8) or bc3 "
                   "(with alpha, 4:1); the block formats need P + 2B a multiple of 4")
      ->check(CLI::IsMember(namesOf(kPageFormatNames)));
  command->add_option("--threads", options->threads, "Worker threads (0: every core)")
      ->check(workerCount());
  command->add_option("--keep-free", options->keepFree,
                      "Bytes of disk that must stay free after the build (0)");
  command->add_flag("--ancestor-errors", options->ancestorErrors,
                    "Also measure each page's error (1 - SSIM, 8 x 8 windows) through every "
                    "ancestor and store it (file version 3), for --ancestors gain_ssim");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar");
  command->callback([options] {
    LayoutOverrides overrides{options->pageSize, options->border, options->channels,
                              options->side,     std::nullopt,    std::nullopt};
    if (!options->colorSpace.empty()) overrides.colorSpace = parseColorSpace(options->colorSpace);
    if (!options->filter.empty()) overrides.filter = parseMipFilter(options->filter);
    if (!options->format.empty()) overrides.format = parsePageFormat(options->format);
    const std::filesystem::path input = options->input;
    // Arguments against each other, and against the page size of an image's layout (128 unless
    // given); a layout file's own page size is checked with the file.
    if (options->pageSize || input.extension() != ".json") {
      const uint32_t pageSize = options->pageSize.value_or(128);
      if (options->border && *options->border >= pageSize)
        throw CLI::ValidationError("--border", std::to_string(*options->border) +
                                                   " is not smaller than the page size " +
                                                   std::to_string(pageSize));
      if (options->side &&
          (*options->side < pageSize || *options->side > (uint64_t{pageSize} << kMaxLevel)))
        throw CLI::ValidationError("--side", std::to_string(*options->side) +
                                                 " is not the page size " +
                                                 std::to_string(pageSize) +
                                                 " times 2^L, L <= " + std::to_string(kMaxLevel));
    }
    buildTexture({.input = input,
                  .overrides = overrides,
                  .options = {options->threads, !options->quiet, options->keepFree,
                              options->ancestorErrors},
                  .output = options->output},
                 std::cout);
  });
}

}  // namespace vt
