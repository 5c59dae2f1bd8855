#pragma once
// JSON text of an input file (layouts, camera paths), parsed with its nesting limited: the
// formats nest a few levels, and a value nested thousands deep would overflow the stack of every
// recursive walk over it (printing it in an error message, for one). Malformed text throws
// nlohmann::json::parse_error as json::parse does; nesting deeper than kMaxJsonDepth throws
// InputError naming the file.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "common/error.h"
#include "common/input_file.h"

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

// The message of a JSON error without nlohmann's "[json.exception.type_error.302] " prefix, e.g.
// "key 'width' not found" or "type must be string, but is null".
inline std::string jsonErrorText(const nlohmann::json::exception& e) {
  const std::string text = e.what();
  const size_t end = text.starts_with("[json.exception.") ? text.find("] ") : std::string::npos;
  return end == std::string::npos ? text : text.substr(end + 2);
}

// The whole of `file` parsed as above, read by readTextFile (common/input_file.h).
inline nlohmann::json readJsonFile(const std::filesystem::path& file, const std::string& what) {
  return parseJsonText(readTextFile(file, "the " + what), file);
}

}  // namespace vt
