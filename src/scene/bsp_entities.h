#pragma once
// The entity lump of a Quake 3 map: a sequence of { "key" "value" ... } blocks.

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

using BspEntity = std::map<std::string, std::string>;

// Parses the entity text. Unbalanced braces or an unterminated string are an InputError naming
// `name` and the line.
std::vector<BspEntity> parseEntities(std::string_view text, const std::string& name);

}  // namespace vt
