#pragma once
// JSON text of an input file (layouts, camera paths), parsed with its nesting limited: the
// formats nest a few levels, and a value nested thousands deep would overflow the stack of every
// recursive walk over it (printing it in an error message, for one). Malformed text throws
// nlohmann::json::parse_error as json::parse does; nesting deeper than kMaxJsonDepth throws
// InputError naming the file.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "common/error.h"

namespace vt {

inline constexpr int kMaxJsonDepth = 64;

inline nlohmann::json parseJsonText(std::string_view text, const std::filesystem::path& file) {
  return nlohmann::json::parse(
      text.begin(), text.end(), [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
        if (depth > kMaxJsonDepth)
          throw InputError(file, "the JSON text nests deeper than the limit of " +
                                     std::to_string(kMaxJsonDepth) + " levels");
        return true;
      });
}

// The whole of `file` parsed as above; InputError "cannot open the <what>" when it cannot be read.
inline nlohmann::json readJsonFile(const std::filesystem::path& file, const std::string& what) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open the " + what);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parseJsonText(text, file);
}

}  // namespace vt
