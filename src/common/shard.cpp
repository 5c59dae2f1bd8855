#include "common/shard.h"

#include <charconv>
#include <stdexcept>

#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/posix_file.h"

namespace vt {
namespace {

constexpr const char* kFormat = "vt-shard";
constexpr int kVersion = 1;

uint32_t wholeNumber(std::string_view digits, std::string_view text) {
  uint32_t value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size())
    throw std::invalid_argument("\"" + std::string(text) + "\"" +
                                ": expected I/N, two whole numbers such as 2/8");
  return value;
}

}  // namespace

std::string Shard::text() const { return std::to_string(index) + "/" + std::to_string(count); }

bool Shard::holdsInTurn(size_t item) const { return item % count == index - 1; }

std::pair<size_t, size_t> Shard::block(size_t items) const {
  // Shard i takes floor(i items / N) to floor((i + 1) items / N); items * N cannot overflow for
  // any folder or path a machine holds (both are far below 2^32).
  const auto edge = [&](uint64_t i) { return static_cast<size_t>(i * items / count); };
  return {edge(index - 1), edge(index)};
}

Shard parseShard(std::string_view text) {
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos)
    throw std::invalid_argument("\"" + std::string(text) + "\"" +
                                ": expected I/N, two whole numbers such as 2/8");
  const Shard shard{wholeNumber(text.substr(0, slash), text),
                    wholeNumber(text.substr(slash + 1), text)};
  if (shard.count < 1 || shard.count > kMaxShards)
    throw std::invalid_argument("\"" + std::string(text) + "\"" + ": N must be 1 to " +
                                std::to_string(kMaxShards));
  if (shard.index < 1 || shard.index > shard.count)
    throw std::invalid_argument("\"" + std::string(text) + "\"" + ": I must be 1 to N");
  return shard;
}

std::optional<Shard> parseShardOption(std::string_view text) {
  if (text.empty()) return std::nullopt;
  return parseShard(text);
}

void writeShardFile(const std::filesystem::path& folder, const ShardFile& record) {
  const nlohmann::json json = {{"format", kFormat},         {"version", kVersion},
                               {"command", record.command}, {"shard", record.shard.text()},
                               {"inputs", record.inputs},   {"items", record.items},
                               {"records", record.records}};
  writeFileAtomically(folder / "shard.json", json.dump(1) + "\n");
}

ShardFile readShardFile(const std::filesystem::path& folder) {
  ShardFile record;
  record.file = folder / "shard.json";
  try {
    const nlohmann::json json = readJsonFile(record.file, "shard record");
    if (!json.is_object() || json.value("format", "") != kFormat)
      throw InputError(record.file, "not a shard record (\"format\": \"vt-shard\")");
    // Compared as JSON: a number a file gives is never converted to int (1e300 would not fit).
    const nlohmann::json& version = json.at("version");
    if (!version.is_number_integer() || version != kVersion)
      throw InputError(record.file, "shard record version " + json.at("version").dump() +
                                        ", this vt reads version " + std::to_string(kVersion));
    record.command = json.at("command").get<std::string>();
    try {
      record.shard = parseShard(json.at("shard").get<std::string>());
    } catch (const std::invalid_argument& e) {
      throw InputError(record.file, std::string("\"shard\": ") + e.what());
    }
    record.inputs = json.at("inputs");
    record.items = json.at("items").get<std::vector<std::string>>();
    record.records = json.at("records");
    if (!record.inputs.is_object() || !record.records.is_array())
      throw InputError(record.file, "\"inputs\" must be an object and \"records\" an array");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(record.file, "malformed shard record: " + jsonErrorText(e));
  }
  return record;
}

void copyShardFile(const ShardFile& shard, const std::string& name, const std::string& what,
                   const std::filesystem::path& to) {
  const std::filesystem::path from = shard.file.parent_path() / name;
  requireRegularFile(from, what);
  std::filesystem::copy_file(from, to / name);
}

std::vector<ShardFile> requireCompleteJob(std::vector<ShardFile> shards) {
  if (shards.empty()) throw std::invalid_argument("merge: no shards");
  const ShardFile& first = shards.front();
  std::vector<const ShardFile*> byIndex(first.shard.count, nullptr);
  for (const ShardFile& s : shards) {
    if (s.command != first.command || s.shard.count != first.shard.count ||
        s.inputs != first.inputs || s.items != first.items)
      throw InputError(s.file, "not a shard of the same job as " + first.file.string() +
                                   " (another command, shard count, inputs or items)");
    const ShardFile*& slot = byIndex[s.shard.index - 1];
    if (slot)
      throw InputError(s.file, "shard " + s.shard.text() + " is also " + slot->file.string());
    slot = &s;
  }
  for (uint32_t i = 0; i < first.shard.count; ++i)
    if (!byIndex[i])
      throw InputError(
          first.file, "shard " + Shard{i + 1, first.shard.count}.text() + " of the job is missing");
  std::vector<ShardFile> ordered;
  ordered.reserve(shards.size());
  for (const ShardFile* s : byIndex) ordered.push_back(*s);
  return ordered;
}

}  // namespace vt
