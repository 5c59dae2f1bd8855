// Fuzz target: the virtual-texture file reader (format/virtual_texture_reader.h).

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/checksum.h"
#include "common/little_endian.h"
#include "format/file_header.h"
#include "format/virtual_texture_reader.h"
#include "fuzz/fuzz_targets.h"

namespace vt::fuzz {
namespace {

// Header fields the checksums depend on (file_header.h).
constexpr size_t kIndexOffsetAt = 56, kDataOffsetAt = 80, kTablesChecksumAt = 96,
                 kHeaderChecksumAt = 120;

// The checksums a correct writer would have stored for these fields and tables.
void recomputeChecksums(std::vector<std::byte>& bytes) {
  if (bytes.size() < kHeaderBytes) return;
  const uint64_t tablesBegin = loadU64(bytes.data() + kIndexOffsetAt),
                 tablesEnd = loadU64(bytes.data() + kDataOffsetAt);
  if (tablesBegin <= tablesEnd && tablesEnd <= bytes.size())
    storeU64(bytes.data() + kTablesChecksumAt,
             checksum64(std::span(bytes).subspan(tablesBegin, tablesEnd - tablesBegin)));
  storeU64(bytes.data() + kHeaderChecksumAt,
           headerChecksum(std::span(bytes).first<kHeaderBytes>()));
}

// A file in memory with a path the reader can open (/proc/self/fd/N), removed with the object.
class MemoryFile {
 public:
  explicit MemoryFile(std::span<const std::byte> bytes) : fd_(::memfd_create("vt-fuzz", 0)) {
    if (fd_ < 0) throw std::runtime_error("memfd_create failed");
    for (size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n <= 0) throw std::runtime_error("cannot write the memory file");
      done += static_cast<size_t>(n);
    }
  }
  ~MemoryFile() { ::close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;

  std::filesystem::path path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

}  // namespace

void virtualTextureFile(Input input) {
  std::vector<std::byte> bytes(input.size());
  std::transform(input.begin(), input.end(), bytes.begin(), [](uint8_t b) { return std::byte(b); });
  recomputeChecksums(bytes);
  const MemoryFile file(bytes);
  const VirtualTextureReader reader(file.path());
  reader.storedPagesPerLevel();
  // The first pages of the file: a damaged page is an InputError of its own, the next is read.
  const uint64_t pages = std::min<uint64_t>(reader.storedPageCount(), 64);
  for (uint64_t slot = 0; slot < pages; ++slot) {
    const PageId page = fromAbsoluteIndex(reader.storedPage(slot));
    reader.noiseValue(page);
    try {
      reader.readPage(page);
    } catch (const InputError&) {
    }
  }
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::virtualTextureFile)
