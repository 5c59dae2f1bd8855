// Fuzz target: the virtual-texture file reader (format/virtual_texture_reader.h) and the block
// decoder of its compressed pages (format/block_decoding.h).

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/checksum.h"
#include "common/little_endian.h"
#include "format/block_decoding.h"
#include "format/file_header.h"
#include "format/virtual_texture_reader.h"
#include "fuzz/fuzz_targets.h"

namespace vt::fuzz {
namespace {

// Header fields the checksums depend on (file_header.h).
constexpr size_t kPageSizeAt = 16, kBorderAt = 20, kChannelsAt = 28, kPixelFormatAt = 32,
                 kStoredPageCountAt = 48, kIndexOffsetAt = 56, kChecksumOffsetAt = 72,
                 kDataOffsetAt = 80, kTablesChecksumAt = 96, kAncestorErrorOffsetAt = 104,
                 kAncestorErrorChecksumAt = 112, kHeaderChecksumAt = 120;
// The pages read (and so the page checksums recomputed) of each file, and those of them whose
// decoded texels are checked against their ranges (a range costs about as much as decoding every
// member: on every page the fuzzer would run 50 times slower).
constexpr uint64_t kPagesRead = 64, kPagesRangeChecked = 2;

// The bytes of one stored page as the header describes it (TextureDescription::storedPageBytes),
// 0 for a description the reader refuses anyway.
uint64_t storedPageBytes(const std::vector<std::byte>& bytes) {
  const uint64_t side = uint64_t{loadU32(bytes.data() + kPageSizeAt)} +
                        2 * uint64_t{loadU32(bytes.data() + kBorderAt)};
  if (side > 2 * kMaxPageSize) return 0;
  switch (loadU32(bytes.data() + kPixelFormatAt)) {
    case static_cast<uint32_t>(PixelFormat::kUnorm8):
      return side * side * std::min(loadU32(bytes.data() + kChannelsAt), kMaxChannels);
    case static_cast<uint32_t>(PixelFormat::kBc1):
      return (side / 4) * (side / 4) * 8;
    case static_cast<uint32_t>(PixelFormat::kBc3):
      return (side / 4) * (side / 4) * 16;
  }
  return 0;
}

// The checksums of the first pages, where both the page and its table entry lie in the file.
void recomputePageChecksums(std::vector<std::byte>& bytes) {
  const uint64_t pageBytes = storedPageBytes(bytes),
                 pages = std::min(loadU64(bytes.data() + kStoredPageCountAt), kPagesRead),
                 table = loadU64(bytes.data() + kChecksumOffsetAt),
                 data = loadU64(bytes.data() + kDataOffsetAt);
  if (pageBytes == 0 || table > bytes.size() || data > bytes.size()) return;
  for (uint64_t k = 0; k < pages; ++k) {
    if (8 * (k + 1) > bytes.size() - table || pageBytes * (k + 1) > bytes.size() - data) return;
    storeU64(bytes.data() + table + 8 * k,
             checksum64(std::span(bytes).subspan(data + pageBytes * k, pageBytes)));
  }
}

// The checksums a correct writer would have stored for these fields, tables and pages.
void recomputeChecksums(std::vector<std::byte>& bytes) {
  if (bytes.size() < kHeaderBytes) return;
  recomputePageChecksums(bytes);
  const uint64_t tablesBegin = loadU64(bytes.data() + kIndexOffsetAt),
                 tablesEnd = loadU64(bytes.data() + kDataOffsetAt);
  if (tablesBegin <= tablesEnd && tablesEnd <= bytes.size())
    storeU64(bytes.data() + kTablesChecksumAt,
             checksum64(std::span(bytes).subspan(tablesBegin, tablesEnd - tablesBegin)));
  // The ancestor errors (version 3) run from their offset to the end of the file.
  if (const uint64_t errors = loadU64(bytes.data() + kAncestorErrorOffsetAt);
      errors != 0 && errors <= bytes.size())
    storeU64(bytes.data() + kAncestorErrorChecksumAt,
             checksum64(std::span(bytes).subspan(errors)));
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

// One decoding per palette rule, the weights member with the H100's measured weights
// (data/gpus/nvidia-h100/model.json). Page k of a file of n bytes is decoded under
// kDecodings[(k + n) % 6]: a mutation that changes the size moves the range-checked pages to other
// rules.
const BlockDecoding kDecodings[] = {
    {PaletteRule::kNearest, PaletteRule::kNearest},
    {PaletteRule::kTruncated, PaletteRule::kTruncated},
    {PaletteRule::kFixedPointLerp, PaletteRule::kFixedPointLerp},
    {PaletteRule::kFixedPointLerpFlooredHalf, PaletteRule::kFixedPointLerp},
    {PaletteRule::kAmd, PaletteRule::kNearest},
    {PaletteRule::kNvidia,
     PaletteRule::kWeights,
     {578, 1156, 1784, 2312, 2940, 3518, 770, 1540, 2556, 3326}},
};

// Every texel of every block of a compressed page, as `decoding` decodes it, lies in the range
// any conforming implementation may return (decodeTexelRange): the oracle judges by that range.
void checkDecodedRanges(const VirtualTextureReader& reader, PageId page,
                        const BlockDecoding& decoding) {
  const TextureDescription& d = reader.description();
  const std::vector<std::byte> blocks = reader.readStoredPage(page);
  const size_t step = blockBytes(d.format);
  for (size_t at = 0; at + step <= blocks.size(); at += step) {
    const std::array<BlockTexel, 16> texels = decodeBlock(d.format, blocks.data() + at, decoding);
    for (uint32_t t = 0; t < 16; ++t) {
      const std::array<BlockTexel, 2> range = decodeTexelRange(d.format, blocks.data() + at, t);
      for (size_t c = 0; c < 4; ++c)
        if (texels[t][c] < range[0][c] || texels[t][c] > range[1][c])
          throw std::logic_error("block " + std::to_string(at / step) + " texel " +
                                 std::to_string(t) + " channel " + std::to_string(c) + ": " +
                                 std::to_string(texels[t][c]) + " outside the range " +
                                 std::to_string(range[0][c]) + ".." + std::to_string(range[1][c]));
    }
  }
}

}  // namespace

void virtualTextureFile(Input input) {
  std::vector<std::byte> bytes(input.size());
  std::transform(input.begin(), input.end(), bytes.begin(), [](uint8_t b) { return std::byte(b); });
  recomputeChecksums(bytes);
  const MemoryFile file(bytes);
  const VirtualTextureReader reader(file.path());
  reader.storedPagesPerLevel();
  // The first pages of the file: a damaged page is an InputError of its own, the next is read.
  const uint64_t pages = std::min(reader.storedPageCount(), kPagesRead);
  for (uint64_t slot = 0; slot < pages; ++slot) {
    const PageId page = fromAbsoluteIndex(reader.storedPage(slot));
    reader.noiseValue(page);
    for (const float error : reader.ancestorErrors(page))
      if (!(error >= 0.0f && error <= 2.0f))
        throw std::logic_error("the reader passed an ancestor error outside [0, 2]");
    const BlockDecoding& decoding = kDecodings[(slot + bytes.size()) % std::size(kDecodings)];
    try {
      reader.readPage(page, decoding);
      if (isBlockCompressed(reader.description().format) && slot < kPagesRangeChecked)
        checkDecodedRanges(reader, page, decoding);
    } catch (const InputError&) {
    }
  }
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::virtualTextureFile)
