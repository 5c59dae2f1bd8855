// Fuzz target: the configuration files users write for chapter 4's runs: a configurations file of
// `vt eval --configs` (eval/configurations_file.h) and one configuration of `vt fly`, `vt inspect`
// and `vt golden generate --config` (eval/flight_configuration.h, read as cli/
// configuration_options.cpp reads it), each configuration that reads written and read back, and
// the cache it asks of a texture.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "common/json_text.h"
#include "eval/configurations_file.h"
#include "eval/flight_configuration.h"
#include "fuzz/fuzz_files.h"
#include "fuzz/fuzz_targets.h"

namespace vt::fuzz {
namespace {

// Written and read back, a configuration must be the same one; and the cache it asks of a
// texture of small unorm8 pages and of large bc1 pages must be from 1 to 256 frames a side.
void checkConfiguration(const FlightConfiguration& configuration) {
  const nlohmann::json written = configuration.toJson();
  FlightConfiguration reread;
  try {
    reread = FlightConfiguration::fromJson(written, FlightConfiguration{});
  } catch (const std::invalid_argument& e) {
    throw std::logic_error(std::string("a written configuration does not read: ") + e.what());
  }
  if (reread.toJson() != written)
    throw std::logic_error("a written configuration reads back as another: " + written.dump() +
                           " and " + reread.toJson().dump());
  TextureDescription smallPages{.pageSize = 8, .border = 1, .levelCount = 4, .channels = 1};
  TextureDescription largeBlocks{.pageSize = 4096, .border = 2, .levelCount = 2};
  largeBlocks.format = PixelFormat::kBc1;
  for (const TextureDescription& texture : {smallPages, largeBlocks}) {
    const uint32_t frames = cacheFramesFor(configuration, texture);
    if (frames < 1 || frames > 256)
      throw std::logic_error("a cache of " + std::to_string(frames) + " frames a side");
  }
}

// The text as one configuration of --config, as ConfigurationOptions::configuration reads it.
FlightConfiguration readOneConfiguration(const std::filesystem::path& file) {
  try {
    return FlightConfiguration::fromJson(readJsonFile(file, "configuration"),
                                         FlightConfiguration{});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "not a configuration: " + jsonErrorText(e));
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace

void configurationFile(Input input) {
  static const ScratchFolder folder("config");
  const std::filesystem::path file = folder.path() / "configs.json";
  writeBytes(file, textOf(input));
  try {
    checkConfiguration(readOneConfiguration(file));
  } catch (const InputError&) {
    // Most configurations files are no single configuration: the file is read as one next.
  }
  for (const FlightConfiguration& configuration : loadConfigurationsFile(file).configurations)
    checkConfiguration(configuration);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::configurationFile)
