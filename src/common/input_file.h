#pragma once
// How every input file is opened: checked to be a regular file before anything reads it, so that
// a FIFO, a device (/dev/zero) or a folder given where a file belongs is refused with one line
// instead of hanging, reading without end or failing deep inside a parser. Text inputs (JSON
// layouts, camera paths, configurations, golden and capture manifests, OBJ and MTL files) are read
// whole, under kMaxTextFileBytes, by readTextFile.

#include <cstdint>
#include <filesystem>
#include <string>

namespace vt {

// Bytes one text input may hold: 256 MiB (q3dm6ish's retextured OBJ is 1.3 MB, the largest
// layout of chapter 4 under 100 KB).
inline constexpr uint64_t kMaxTextFileBytes = uint64_t{256} << 20;

// Throws InputError "<file>: cannot open <what>: <reason>" or "<file>: cannot read <what>: it is a
// folder" ("... it is a FIFO, not a regular file") unless `file` names a regular file; also when
// its name holds a NUL character (it would be cut there). `what` is a noun phrase ("mesh", "the
// configuration"). For inputs a library opens by name (images, archives).
void requireRegularFile(const std::filesystem::path& file, const std::string& what);

// The whole of `file`, a regular file of at most `limit` bytes (InputError naming the file and
// the limit otherwise). Opened without blocking, so a FIFO is refused rather than waited on.
std::string readTextFile(const std::filesystem::path& file, const std::string& what,
                         uint64_t limit = kMaxTextFileBytes);

}  // namespace vt
