#pragma once
// JSON files the tests read back (reports, summaries): parsed whole, with nlohmann-json.

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace vt::test {

inline nlohmann::json readJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace vt::test
