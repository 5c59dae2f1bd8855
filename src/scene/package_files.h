#pragma once
// The files of a Quake 3 game folder: the union of its .pk3 archives (zip files, read with libzip),
// where an archive later in load order overrides an earlier one's file of the same name, as the
// game does (it loads a folder's archives in the order of their names). Names are compared without
// regard to case (ASCII only) and with '/' as the separator (a backslash in a name reads as '/').
// Entries whose names end in '/' are folders, not files.
//
// The archives stay open for the object's lifetime and every call, const ones included, reads
// through libzip handles, which are not thread-safe: a PackageFiles is used by one thread at a
// time.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/resource_limits.h"

namespace vt {

// The key a name is compared by: ASCII lower case, '/' as the separator (file names, and shader
// names, which the game compares the same way).
std::string packageNameKey(std::string_view name);

class PackageFiles {
 public:
  // Opens the archives in load order (the last one wins). A file that is not a readable zip
  // archive is an InputError naming it.
  explicit PackageFiles(const std::vector<std::filesystem::path>& archives);
  // Every *.pk3 of each folder (in the order given), each folder's archives sorted by name.
  static PackageFiles fromFolders(const std::vector<std::filesystem::path>& folders);
  // One archive held in memory (tests, fuzzing); `name` stands for its path in messages.
  static PackageFiles fromMemory(const std::filesystem::path& name, std::vector<uint8_t> archive);

  PackageFiles(PackageFiles&&) noexcept;
  PackageFiles& operator=(PackageFiles&&) noexcept;
  ~PackageFiles();

  // The name as stored in the winning archive, or nothing.
  std::optional<std::string> find(std::string_view name) const;
  // The file's bytes; an InputError naming archive and entry if it is missing, cannot be inflated,
  // or would inflate to more than its directory entry says or than `limit` (by default
  // kMaxPackageEntryBytes, common/resource_limits.h).
  std::vector<uint8_t> read(std::string_view name, uint64_t limit = kMaxPackageEntryBytes) const;
  // Every file whose name starts with `prefix` and ends with `suffix` (case-insensitive), as
  // stored, sorted by lower-cased name.
  std::vector<std::string> list(std::string_view prefix, std::string_view suffix) const;
  // "<archive path>:<entry>" for messages; just the name when no archive holds it.
  std::string describe(std::string_view name) const;

 private:
  struct Archives;
  PackageFiles();
  std::unique_ptr<Archives> archives_;
};

}  // namespace vt
