#pragma once
// What `vt info` and `vt demo` say about a virtual-texture file: one JSON document, also printed
// as aligned text, so both forms always hold the same facts.

#include <nlohmann/json.hpp>
#include <string>

#include "format/virtual_texture_reader.h"

namespace vt {

nlohmann::json textureReport(const VirtualTextureReader& reader);
std::string formatTextureReport(const nlohmann::json& report);

// Reads every stored page and checks its checksum; throws InputError naming the first bad page.
// Returns the number of pages read.
uint64_t verifyAllPages(const VirtualTextureReader& reader);

}  // namespace vt
