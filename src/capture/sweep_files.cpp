#include "capture/sweep_files.h"

#include <bit>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>
#include <span>

#include "common/delta_coding.h"
#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/posix_file.h"

namespace vt::capture {
namespace {

constexpr size_t kMaxSweeps = 8;
constexpr size_t kMaxExpressionBytes = 256;
constexpr size_t kMaxNameBytes = 32;
// The one target a request names; a sweep of the result's bits names none, as before targets.
constexpr const char* kDepth24Target = "depth24";

std::filesystem::path resultFile(const std::filesystem::path& folder,
                                 const calibrate::FunctionSweep& sweep) {
  return folder / ("sweep-" + sweep.name + ".delta");
}

bool validName(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameBytes) return false;
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

uint32_t wholeField(const nlohmann::json& j, const char* key, uint64_t lo, uint64_t hi,
                    const std::filesystem::path& file, const std::string& where) {
  const nlohmann::json& value = j.at(key);
  if (!value.is_number_unsigned() || value.get<uint64_t>() < lo || value.get<uint64_t>() > hi)
    throw InputError(file, where + "field " + key + " is not a whole number from " +
                               std::to_string(lo) + " to " + std::to_string(hi));
  return static_cast<uint32_t>(value.get<uint64_t>());
}

void refuseUnknownFields(const nlohmann::json& j, const std::set<std::string>& known,
                         const std::filesystem::path& file, const std::string& where) {
  for (const auto& item : j.items())
    if (!known.contains(item.key()))
      throw InputError(file, where + "field " + item.key() + " is not a field of a sweep here");
}

calibrate::FunctionSweep readSweep(const nlohmann::json& j, const std::filesystem::path& file,
                                   const std::string& where) {
  if (!j.is_object()) throw InputError(file, where + "is not an object");
  refuseUnknownFields(j, {"name", "expression", "first", "count", "target"}, file, where);
  calibrate::FunctionSweep s;
  s.name = j.at("name").get<std::string>();
  if (!validName(s.name))
    throw InputError(file, where + "field name is not 1 to 32 of a-z, 0-9 and _");
  s.expression = j.at("expression").get<std::string>();
  if (s.expression.empty() || s.expression.size() > kMaxExpressionBytes)
    throw InputError(file, where + "field expression is not 1 to 256 bytes");
  s.first = wholeField(j, "first", 0, 0xffffffffu, file, where);
  s.count = wholeField(j, "count", calibrate::kSweepWidth, calibrate::kMaxSweepCount, file, where);
  if (s.count % calibrate::kSweepWidth != 0)
    throw InputError(
        file, where + "field count is not a multiple of " + std::to_string(calibrate::kSweepWidth));
  if (uint64_t{s.first} + s.count > (uint64_t{1} << 32))
    throw InputError(file,
                     where + "the inputs run past the last float bits (first + count > 2^32)");
  if (j.contains("target")) {
    if (j.at("target") != kDepth24Target)
      throw InputError(file, where + "field target is not \"" + kDepth24Target +
                                 "\" (a sweep without it writes the result's bits)");
    s.target = calibrate::SweepTarget::kDepth24;
  }
  return s;
}

}  // namespace

void writeSweepRequests(const std::filesystem::path& folder,
                        const std::vector<calibrate::FunctionSweep>& sweeps) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const calibrate::FunctionSweep& s : sweeps) {
    list.push_back(
        {{"name", s.name}, {"expression", s.expression}, {"first", s.first}, {"count", s.count}});
    if (s.target == calibrate::SweepTarget::kDepth24) list.back()["target"] = kDepth24Target;
  }
  const nlohmann::ordered_json j = {{"format", "vt-sweeps"}, {"version", 1}, {"sweeps", list}};
  writeFileAtomically(folder / "sweeps.json", j.dump(1) + "\n");
}

std::vector<calibrate::FunctionSweep> readSweepRequests(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "sweeps.json";
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return {};
  try {
    const nlohmann::json j = readJsonFile(file, "sweep requests");
    if (!j.is_object()) throw InputError(file, "is not a vt-sweeps object");
    refuseUnknownFields(j, {"format", "version", "sweeps"}, file, "");
    if (j.at("format") != "vt-sweeps" || j.at("version") != 1)
      throw InputError(file, "not a vt-sweeps description of version 1");
    const nlohmann::json& list = j.at("sweeps");
    if (!list.is_array() || list.size() > kMaxSweeps)
      throw InputError(
          file, "field sweeps is not a list of at most " + std::to_string(kMaxSweeps) + " sweeps");
    std::vector<calibrate::FunctionSweep> sweeps;
    std::set<std::string> names;
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string where = "sweep " + std::to_string(k) + ": ";
      sweeps.push_back(readSweep(list[k], file, where));
      if (!names.insert(sweeps.back().name).second)
        throw InputError(file, where + "a second sweep named " + sweeps.back().name);
    }
    return sweeps;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, jsonErrorText(e));
  }
}

void writeSweepResult(const std::filesystem::path& folder, const calibrate::FunctionSweep& sweep,
                      const std::vector<uint32_t>& bits) {
  const std::string bytes = deltaCoded(bits);
  writeFileAtomically(resultFile(folder, sweep), std::as_bytes(std::span(bytes)));
}

std::optional<std::vector<uint32_t>> readSweepResult(const std::filesystem::path& folder,
                                                     const calibrate::FunctionSweep& sweep) {
  const std::filesystem::path file = resultFile(folder, sweep);
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return std::nullopt;
  const uint64_t expected = uint64_t{sweep.count} * sizeof(uint32_t);
  const std::string bytes = readTextFile(file, "sweep results", expected);
  if (bytes.size() != expected)
    throw InputError(file, "sweep results: " + std::to_string(bytes.size()) + " bytes, expected " +
                               std::to_string(expected) + " (" + std::to_string(sweep.count) +
                               " results of " + sweep.name + ")");
  return deltaDecoded(bytes);
}

}  // namespace vt::capture
