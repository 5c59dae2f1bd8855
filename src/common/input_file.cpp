#include "common/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "common/error.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"

namespace vt {

void requireRegularFile(const std::filesystem::path& file, const std::string& what) {
  if (file.native().find('\0') != std::string::npos)
    throw InputError(file.native().substr(0, file.native().find('\0')),
                     "the name of " + what + " holds a NUL character (it would be cut there)");
  struct stat info {};
  if (::stat(file.c_str(), &info) != 0)
    throw InputError(file, "cannot open " + what + ": " + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) throw InputError(file, "cannot read " + what + ": it is a folder");
  if (!S_ISREG(info.st_mode))
    throw InputError(file, "cannot read " + what + ": it is " +
                               (S_ISFIFO(info.st_mode)   ? "a FIFO"
                                : S_ISCHR(info.st_mode)  ? "a character device"
                                : S_ISBLK(info.st_mode)  ? "a block device"
                                : S_ISSOCK(info.st_mode) ? "a socket"
                                                         : "a special file") +
                               ", not a regular file");
}

std::string readTextFile(const std::filesystem::path& file, const std::string& what,
                         uint64_t limit) {
  requireRegularFile(file, what);
  // The check above names what is wrong; opening checks again, on the descriptor read from.
  const PosixFile input = PosixFile::openForReading(file);
  const uint64_t size = input.size();
  if (size > limit) throw limitError(file, "reading " + what, size, limit, " bytes");
  std::string text(size, '\0');
  input.readExact(0, std::as_writable_bytes(std::span(text.data(), text.size())));
  return text;
}

}  // namespace vt
