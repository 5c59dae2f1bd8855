#pragma once
// A file descriptor owned by value (RAII) with whole-buffer positional reads and writes.
// Positional I/O (pread/pwrite) keeps no file offset, so one open file serves many threads.
// Every failure throws InputError naming the file and the system's reason.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace vt {

class PosixFile {
 public:
  static PosixFile openForReading(const std::filesystem::path& path);

  PosixFile(PosixFile&& other) noexcept;
  PosixFile& operator=(PosixFile&& other) noexcept;
  PosixFile(const PosixFile&) = delete;
  PosixFile& operator=(const PosixFile&) = delete;
  ~PosixFile();

  uint64_t size() const;
  // Reads exactly bytes.size() bytes at `offset`; a short file is an error.
  void readExact(uint64_t offset, std::span<std::byte> bytes) const;
  void writeAll(uint64_t offset, std::span<const std::byte> bytes) const;
  void resize(uint64_t bytes) const;
  void sync() const;

  const std::filesystem::path& path() const { return path_; }

 private:
  friend class TemporaryFile;
  PosixFile(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}

  int fd_ = -1;
  std::filesystem::path path_;
};

// A new file next to `destination` that becomes `destination` on commit(), atomically (rename),
// and is removed if destroyed before: readers of `destination` see the old file or the complete
// new one, never a partial file.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::filesystem::path& destination);
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile();

  const PosixFile& file() const { return file_; }
  const std::filesystem::path& destination() const { return destination_; }
  // Flushes the data to disk, renames the file to its destination and flushes the directory.
  void commit();

 private:
  std::filesystem::path destination_;
  PosixFile file_;
  bool committed_ = false;
};

// A new folder next to `destination` ("<parent>/.<name>.tmp-XXXXXX") that takes its place on
// commit(), for outputs of several files (evaluation results, golden sets): readers of
// `destination` see the previous folder or the complete new one, never a mix. commit() exchanges
// the two atomically (renameat2 with RENAME_EXCHANGE, or a plain rename when there was none) and
// then removes the previous folder. Destroyed before commit(), it removes the new folder.
//
// Replacing a folder removes what it held, so a destination that exists must be an empty folder
// or a previous output of the same kind, recognised by `marker`, a file every such output holds:
// anything else is refused with InputError before any work is done.
class TemporaryFolder {
 public:
  // Throws InputError when `destination` is a file, or a folder that is neither empty nor holds
  // `marker`: for commands that check their output folder before long work.
  static void requireReplaceable(const std::filesystem::path& destination,
                                 const std::string& marker);

  TemporaryFolder(const std::filesystem::path& destination, const std::string& marker);
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  ~TemporaryFolder();

  const std::filesystem::path& path() const { return path_; }
  void commit();

 private:
  std::filesystem::path destination_, path_;
  std::string marker_;
  bool committed_ = false;
};

}  // namespace vt

namespace vt {

// Writes `bytes` as `path` through a TemporaryFile (the parent folder must exist).
void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);
void writeFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace vt
