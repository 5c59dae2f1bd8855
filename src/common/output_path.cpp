#include "common/output_path.h"

#include <sys/stat.h>

#include <optional>

#include "common/error.h"

namespace vt {
namespace {

// The file's identity, following symbolic links; nothing when it does not exist.
std::optional<struct stat> identity(const std::filesystem::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return std::nullopt;
  return info;
}

bool sameFile(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::filesystem::path pathInside(const std::filesystem::path& root, std::string_view name,
                                 const std::string& source) {
  // The folder by its own name only: `root` may be a temporary folder taking the output's place.
  const std::filesystem::path folder = (root / "").parent_path().filename();
  const auto refuse = [&](const std::string& why) {
    return InputError(source, "the name '" + std::string(name.substr(0, name.find('\0'))) +
                                  "' leads outside the folder " + folder.string() + "/: " + why);
  };
  if (name.find('\0') != std::string_view::npos) throw refuse("it holds a NUL character");
  const std::filesystem::path relative(name);
  if (relative.empty()) throw refuse("it is empty");
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory())
    throw refuse("it is absolute");
  for (const std::filesystem::path& component : relative)
    if (component == "..") throw refuse("it has a '..' component");
  // Each folder on the way, and the file itself, must be what it says: a symbolic link placed
  // there (by an earlier run, or by another user in a shared folder) could lead anywhere.
  std::filesystem::path path = root, walked = folder;
  bool exists = true;  // below a component that does not exist, none does (made by the writer)
  for (const std::filesystem::path& component : relative) {
    if (component.empty() || component == ".") continue;
    path /= component;
    walked /= component;
    struct stat info {};
    exists = exists && ::lstat(path.c_str(), &info) == 0;
    if (exists && S_ISLNK(info.st_mode)) throw refuse(walked.string() + " is a symbolic link");
  }
  return path;
}

void requireOutputFile(const std::filesystem::path& output,
                       const std::vector<std::filesystem::path>& inputs) {
  const std::optional<struct stat> existing = identity(output);
  if (!existing) return;
  for (const std::filesystem::path& input : inputs) {
    const std::optional<struct stat> in = identity(input);
    if (in && sameFile(*in, *existing))
      throw InputError(output, "is the input " + input.string() +
                                   ": writing it would destroy the input; choose another output");
  }
  if (!S_ISREG(existing->st_mode))
    throw InputError(output, "is " + kindOf(existing->st_mode) +
                                 ", not a regular file: refusing to replace it with the output");
}

void requireOutputFolder(const std::filesystem::path& output,
                         const std::vector<std::filesystem::path>& inputs) {
  const std::optional<struct stat> existing = identity(output);
  if (!existing) return;
  if (!S_ISDIR(existing->st_mode))
    throw InputError(output, "is " + kindOf(existing->st_mode) +
                                 ", not a folder: refusing to replace it with the output folder");
  for (const std::filesystem::path& input : inputs) {
    if (!identity(input)) continue;
    std::error_code error;
    std::filesystem::path ancestor = std::filesystem::weakly_canonical(input, error);
    if (error) continue;
    // The input itself, then each folder above it up to the root.
    for (;;) {
      const std::optional<struct stat> at = identity(ancestor);
      if (at && sameFile(*at, *existing))
        throw InputError(output, "holds the input " + input.string() +
                                     ": replacing the folder would destroy it; choose another "
                                     "output");
      if (ancestor == ancestor.parent_path()) break;
      ancestor = ancestor.parent_path();
    }
  }
}

}  // namespace vt
