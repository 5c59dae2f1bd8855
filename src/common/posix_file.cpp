#include "common/posix_file.h"

#include <fcntl.h>
#include <stdio.h>  // renameat2
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>

#include "common/error.h"

namespace vt {
namespace {

[[noreturn]] void throwSystemError(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path, what + ": " + std::strerror(errno));
}

}  // namespace

PosixFile PosixFile::openForReading(const std::filesystem::path& path) {
  if (path.native().find('\0') != std::string::npos)
    throw InputError(path.native().substr(0, path.native().find('\0')),
                     "the file name holds a NUL character");
  // Without blocking: opening a FIFO would wait for a writer (regular files ignore the flag).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throwSystemError(path, "cannot open");
  PosixFile file(fd, path);
  struct stat info {};
  if (::fstat(fd, &info) != 0) throwSystemError(path, "cannot stat");
  if (!S_ISREG(info.st_mode)) throw InputError(path, "not a regular file");
  return file;
}

PosixFile::PosixFile(PosixFile&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}

PosixFile& PosixFile::operator=(PosixFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
  }
  return *this;
}

PosixFile::~PosixFile() {
  if (fd_ >= 0) ::close(fd_);
}

uint64_t PosixFile::size() const {
  struct stat info {};
  if (::fstat(fd_, &info) != 0) throwSystemError(path_, "cannot stat");
  return static_cast<uint64_t>(info.st_size);
}

void PosixFile::readExact(uint64_t offset, std::span<std::byte> bytes) const {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pread(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throwSystemError(path_, "read failed at byte " + std::to_string(offset + done));
    if (n == 0)
      throw InputError(path_, "unexpected end of file at byte " + std::to_string(offset + done));
    done += static_cast<size_t>(n);
  }
}

void PosixFile::writeAll(uint64_t offset, std::span<const std::byte> bytes) const {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n =
        ::pwrite(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throwSystemError(path_, "write failed at byte " + std::to_string(offset + done));
    done += static_cast<size_t>(n);
  }
}

void PosixFile::resize(uint64_t bytes) const {
  if (::ftruncate(fd_, static_cast<off_t>(bytes)) != 0)
    throwSystemError(path_, "cannot resize to " + std::to_string(bytes) + " bytes");
}

void PosixFile::sync() const {
  if (::fsync(fd_) != 0) throwSystemError(path_, "fsync failed");
}

namespace {

// Creates "<dir>/.<name>.tmp-XXXXXX<ext>" next to `destination`, so that the rename stays within
// one file system and tools that choose a format by extension see the destination's. Returns the
// descriptor and fills `name`.
int createTemporaryNextTo(const std::filesystem::path& destination, std::string& name) {
  const std::filesystem::path directory =
      destination.has_parent_path() ? destination.parent_path() : std::filesystem::path(".");
  const std::string extension = destination.extension().string();
  std::string file = ".";  // built by appends: GCC 12 warns falsely on "." + std::string
  file.append(destination.filename().string()).append(".tmp-XXXXXX").append(extension);
  name = (directory / file).string();
  const int fd = ::mkostemps(name.data(), static_cast<int>(extension.size()), O_CLOEXEC);
  if (fd < 0)
    throwSystemError(destination, "cannot create a temporary file in " + directory.string());
  // mkostemp creates the file 0600; give it the permissions an ordinary new file would get.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  return fd;
}

void syncDirectory(const std::filesystem::path& destination) {
  const std::filesystem::path directory =
      destination.has_parent_path() ? destination.parent_path() : std::filesystem::path(".");
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // the rename is done; a directory we cannot open cannot be synced
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

TemporaryFile::TemporaryFile(const std::filesystem::path& destination)
    : destination_(destination), file_(-1, {}) {
  std::string name;
  const int fd = createTemporaryNextTo(destination, name);
  file_ = PosixFile(fd, name);
}

TemporaryFile::~TemporaryFile() {
  if (!committed_ && file_.fd_ >= 0) ::unlink(file_.path().c_str());
}

void TemporaryFile::commit() {
  file_.sync();
  if (::rename(file_.path().c_str(), destination_.c_str()) != 0)
    throwSystemError(destination_, "cannot rename " + file_.path().string() + " to it");
  committed_ = true;
  syncDirectory(destination_);
}

namespace {

// The folder itself when `destination` ends in a separator or is ".".
std::filesystem::path folderPath(const std::filesystem::path& destination) {
  std::filesystem::path path = std::filesystem::absolute(destination).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  return path;
}

}  // namespace

void TemporaryFolder::requireReplaceable(const std::filesystem::path& destination,
                                         const std::string& marker) {
  const std::filesystem::path folder = folderPath(destination);
  std::error_code error;
  if (!std::filesystem::exists(folder, error)) return;
  if (!std::filesystem::is_directory(folder))
    throw InputError(destination, "is a file, not a folder for the output");
  if (!std::filesystem::is_empty(folder) && !std::filesystem::exists(folder / marker))
    throw InputError(destination, "holds files but no " + marker +
                                      ": not a previous output; give a new or empty folder (its "
                                      "content would be replaced)");
}

TemporaryFolder::TemporaryFolder(const std::filesystem::path& destination,
                                 const std::string& marker)
    : destination_(folderPath(destination)), marker_(marker) {
  requireReplaceable(destination, marker);
  std::filesystem::create_directories(destination_.parent_path());
  std::string name = ".";  // built by appends: GCC 12 warns falsely on "." + std::string
  name.append(destination_.filename().string()).append(".tmp-XXXXXX");
  std::string folder = (destination_.parent_path() / name).string();
  if (::mkdtemp(folder.data()) == nullptr)
    throwSystemError(destination, "cannot create a temporary folder next to it");
  path_ = folder;
  // mkdtemp creates the folder 0700; give it the permissions an ordinary new folder would get.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(path_.c_str(), 0777 & ~mask);
}

TemporaryFolder::~TemporaryFolder() {
  std::error_code ignored;
  if (!committed_) std::filesystem::remove_all(path_, ignored);
}

void TemporaryFolder::commit() {
  const int fd = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  std::error_code error;
  if (std::filesystem::exists(destination_, error)) {
    // Swap, so the destination is never missing; the previous output then lies at path_.
    if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, destination_.c_str(), RENAME_EXCHANGE) !=
        0) {
      if (errno != EINVAL && errno != ENOSYS)
        throwSystemError(destination_, "cannot exchange it with " + path_.string());
      // A file system without the exchange: move the previous folder aside first.
      std::string aside = ".";
      aside.append(destination_.filename().string()).append(".tmp-XXXXXX");
      std::string previous = (destination_.parent_path() / aside).string();
      if (::mkdtemp(previous.data()) == nullptr ||
          ::rename(destination_.c_str(), previous.c_str()) != 0 ||
          ::rename(path_.c_str(), destination_.c_str()) != 0)
        throwSystemError(destination_, "cannot replace it with " + path_.string());
      path_ = previous;
    }
    committed_ = true;
    syncDirectory(destination_);
    // The marker first: a removal cut short leaves a folder that is no longer taken for an output.
    std::filesystem::remove(path_ / marker_, error);
    std::filesystem::remove_all(path_, error);
    return;
  }
  if (::rename(path_.c_str(), destination_.c_str()) != 0)
    throwSystemError(destination_, "cannot rename " + path_.string() + " to it");
  committed_ = true;
  syncDirectory(destination_);
}

}  // namespace vt

namespace vt {

void writeFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  TemporaryFile temporary(path);
  temporary.file().writeAll(0, bytes);
  temporary.commit();
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace vt
