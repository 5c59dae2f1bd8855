#pragma once
// Where a command may write. Two rules, each checked in one place for every command:
//
// - A name taken from an input (an archive entry, a shader stage's image) becomes a path only
//   through pathInside(): it must stay inside the destination folder, lexically (no "..", not
//   absolute, no NUL) and on disk (no symbolic link on the way), or the input is refused.
// - An output given on the command line is checked by requireOutputFile() or
//   requireOutputFolder() before any work: it may not be one of the inputs (compared by device
//   and inode, so another name for the same file is caught), and what exists at its path must be
//   of the output's kind (a regular file, or a folder), never a device, a FIFO or a socket.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

// `root / name`, checked to stay inside `root`: `name` must be relative, without a ".." component
// or a NUL, and no component of it that exists below `root` may be a symbolic link. Throws
// InputError naming `source` (the archive and its entry, for one) otherwise.
std::filesystem::path pathInside(const std::filesystem::path& root, std::string_view name,
                                 const std::string& source);

// Refuses (InputError naming `output`) an output file that is the same file as one of `inputs`
// or that exists and is not a regular file. Inputs that do not exist are skipped.
void requireOutputFile(const std::filesystem::path& output,
                       const std::vector<std::filesystem::path>& inputs);

// Refuses (InputError naming `output`) an output folder that exists and is not a folder, or that
// is one of `inputs` or holds one of them (replacing the folder would remove it).
void requireOutputFolder(const std::filesystem::path& output,
                         const std::vector<std::filesystem::path>& inputs);

}  // namespace vt
