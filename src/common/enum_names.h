#pragma once
// One name table per configuration enum: the names a user writes (command-line options, JSON
// values) and the program writes back, in the order messages list them. Parsing, printing,
// CLI11's checks and every "is not one of ..." message read the table, so each name is spelt once:
//
//   inline constexpr EnumNames<AncestorStrategy, 3> kAncestorStrategyNames = {{
//       {AncestorStrategy::kNone, "none"}, {AncestorStrategy::kIntern, "intern"}, ...}};
//   nameOf(kAncestorStrategyNames, AncestorStrategy::kIntern)   // "intern"
//   findByName(kAncestorStrategyNames, "extern")                // AncestorStrategy::kExtern
//   joinedNames(kAncestorStrategyNames)                         // "none, intern, extern"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

template <class Enum>
struct EnumName {
  Enum value;
  std::string_view name;
};

template <class Enum, std::size_t N>
using EnumNames = std::array<EnumName<Enum>, N>;

// The name of `value`; every table names every value of its enum.
template <class Enum, std::size_t N>
constexpr std::string_view nameOf(const EnumNames<Enum, N>& table, Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return entry.name;
  return "unknown";
}

template <class Enum, std::size_t N>
constexpr std::optional<Enum> findByName(const EnumNames<Enum, N>& table, std::string_view name) {
  for (const EnumName<Enum>& entry : table)
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

// The names in the table's order, e.g. "none, intern, extern", or with lastSeparator " or "
// "1, 2, 4 or 8".
template <class Enum, std::size_t N>
std::string joinedNames(const EnumNames<Enum, N>& table, std::string_view lastSeparator = ", ") {
  std::string text;
  for (std::size_t i = 0; i < N; ++i)
    text.append(i == 0 ? "" : i + 1 == N ? lastSeparator : ", ").append(table[i].name);
  return text;
}

// The names, for CLI::IsMember.
template <class Enum, std::size_t N>
std::vector<std::string> namesOf(const EnumNames<Enum, N>& table) {
  std::vector<std::string> names;
  for (const EnumName<Enum>& entry : table) names.emplace_back(entry.name);
  return names;
}

}  // namespace vt
