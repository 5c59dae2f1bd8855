// Malformed virtual-texture files: each is rejected on open (or, for page data, on read) with one
// InputError that names the file and the field, never with a crash or an out-of-bounds read (the
// sanitizer build runs these too). Offsets are those of the format, file_header.h.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "build/synthetic_texture.h"
#include "common/checksum.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "format/virtual_texture_reader.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr size_t kPageSizeAt = 16, kBorderAt = 20, kLevelCountAt = 24, kChannelsAt = 28,
                 kPixelFormatAt = 32, kColorSpaceAt = 36, kFlagsAt = 40, kReservedAt = 44,
                 kStoredPagesAt = 48, kNoiseOffsetAt = 64, kDataOffsetAt = 80, kFileBytesAt = 88,
                 kTablesChecksumAt = 96, kAncestorErrorOffsetAt = 104,
                 kAncestorErrorChecksumAt = 112, kHeaderChecksumAt = 120, kVersionAt = 8;

class MalformedFile : public ::testing::Test {
 protected:
  void SetUp() override {
    // A sparse texture: P = 8, B = 1, levels 0..3, 13 stored pages (1 + 4 + 4 + 4).
    texture_.description = {.pageSize = 8, .border = 1, .levelCount = 4, .channels = 4};
    texture_.discRadius = 0.1;
    writeSyntheticTexture(dir_ / "valid.vt", texture_);
    valid_ = test::readBytes(dir_ / "valid.vt");
    storedPages_ = loadU64(valid_.data() + kStoredPagesAt);
  }

  // Opens `bytes` as a file and returns the error; fails the test when the file opens.
  std::string openError(const std::vector<std::byte>& bytes) {
    const auto path = dir_ / "bad.vt";
    test::writeBytes(path, bytes);
    try {
      const VirtualTextureReader reader(path);
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), StartsWith(path.string() + ": "));
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      return e.what();
    }
    ADD_FAILURE() << "the malformed file was accepted";
    return {};
  }

  // Patches the header and recomputes its checksum, as a buggy writer would have produced it.
  static std::vector<std::byte> withU32(std::vector<std::byte> bytes, size_t at, uint32_t value) {
    storeU32(bytes.data() + at, value);
    return rehashHeader(std::move(bytes));
  }
  static std::vector<std::byte> withU64(std::vector<std::byte> bytes, size_t at, uint64_t value) {
    storeU64(bytes.data() + at, value);
    return rehashHeader(std::move(bytes));
  }
  static std::vector<std::byte> rehashHeader(std::vector<std::byte> bytes) {
    storeU64(bytes.data() + kHeaderChecksumAt,
             checksum64(std::span<const std::byte>(bytes).first(kHeaderChecksumAt)));
    return bytes;
  }
  // Recomputes the tables checksum after a table was patched, then the header's.
  static std::vector<std::byte> rehashTables(std::vector<std::byte> bytes) {
    const uint64_t dataOffset = loadU64(bytes.data() + kDataOffsetAt);
    storeU64(bytes.data() + kTablesChecksumAt, checksum64(std::span<const std::byte>(bytes).subspan(
                                                   kHeaderBytes, dataOffset - kHeaderBytes)));
    return rehashHeader(std::move(bytes));
  }
  uint64_t noiseOffset() const { return loadU64(valid_.data() + kNoiseOffsetAt); }
  uint64_t dataOffset() const { return loadU64(valid_.data() + kDataOffsetAt); }

  test::ScratchDirectory dir_;
  SyntheticTexture texture_;
  std::vector<std::byte> valid_;
  uint64_t storedPages_ = 0;
};

TEST_F(MalformedFile, TheUnmodifiedFileOpens) {
  EXPECT_EQ(storedPages_, 13u);
  const VirtualTextureReader reader(dir_ / "valid.vt");
  EXPECT_EQ(reader.storedPageCount(), 13u);
}

TEST_F(MalformedFile, TruncatedFiles) {
  EXPECT_THAT(openError({}), HasSubstr("truncated: 0 bytes, a virtual-texture header needs 128"));
  EXPECT_THAT(openError({valid_.begin(), valid_.begin() + 100}), HasSubstr("truncated: 100 bytes"));
  // Cut in the tables, and in the middle of the last page.
  for (const size_t size : {size_t{128}, size_t{200}, valid_.size() - 1}) {
    const std::string error = openError({valid_.begin(), valid_.begin() + static_cast<long>(size)});
    EXPECT_THAT(error, HasSubstr("truncated: the header declares " + std::to_string(valid_.size()) +
                                 " bytes, the file has " + std::to_string(size)));
  }
}

TEST_F(MalformedFile, TrailingBytes) {
  auto bytes = valid_;
  bytes.resize(bytes.size() + 3);
  EXPECT_THAT(openError(bytes), HasSubstr("3 unexpected bytes after the last page"));
}

TEST_F(MalformedFile, WrongMagic) {
  auto bytes = valid_;
  bytes[1] = std::byte{'X'};
  EXPECT_THAT(openError(bytes), HasSubstr("not a virtual-texture file (wrong magic number)"));
  EXPECT_THAT(openError(std::vector<std::byte>(4096, std::byte{'a'})), HasSubstr("wrong magic"));
}

TEST_F(MalformedFile, UnknownVersion) {
  EXPECT_THAT(openError(withU32(valid_, 8, 4)),
              HasSubstr("header field version: 4 is not supported (this build reads versions 1 "
                        "to 3)"));
  EXPECT_THAT(openError(withU32(valid_, 8, 0)), HasSubstr("header field version: 0"));
}

// The block formats (bc1, bc3): their fields against each other and the file's version, and a
// damaged block caught by the page's checksum.
TEST_F(MalformedFile, BlockFormatsThatBreakTheirRules) {
  // An unorm8 file claiming bc1: its version 1 cannot hold it; version 2 then finds 4-channel
  // blocks need P + 2B = 10 a multiple of 4.
  EXPECT_THAT(openError(withU32(valid_, kPixelFormatAt, 2)),
              HasSubstr("header field border: stored pages of 10 texels (P + 2B) are not whole 4 "
                        "x 4 blocks of pixel format bc1"));
  SyntheticTexture bc1 = texture_;
  bc1.description.border = 2;
  bc1.description.format = PixelFormat::kBc1;
  writeSyntheticTexture(dir_ / "bc1.vt", bc1);
  const auto valid = test::readBytes(dir_ / "bc1.vt");
  EXPECT_EQ(loadU32(valid.data() + 8), 2u);
  EXPECT_THAT(openError(withU32(valid, 8, 1)),
              HasSubstr("header field pixel_format: bc1 needs version 2, the file is version 1"));
  EXPECT_THAT(openError(withU32(valid, kChannelsAt, 3)),
              HasSubstr("header field channels: 3 with pixel format bc1, which stores 4"));
  // bc3 pages are twice as large: the declared size no longer matches.
  EXPECT_THAT(openError(withU32(valid, kPixelFormatAt, 3)), HasSubstr("header field file_bytes"));
  // A page whose blocks are one byte short: the file ends early.
  auto truncated = valid;
  truncated.pop_back();
  EXPECT_THAT(openError(truncated), HasSubstr("truncated"));

  auto bytes = valid;
  const uint64_t dataAt = loadU64(valid.data() + kDataOffsetAt);
  bytes[dataAt + 2 * bc1.description.storedPageBytes() + 5] ^= std::byte{0x01};
  test::writeBytes(dir_ / "corrupt.vt", bytes);
  const VirtualTextureReader reader(dir_ / "corrupt.vt");
  EXPECT_THAT([&] { reader.readPage(fromAbsoluteIndex(reader.storedPage(2))); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("checksum mismatch")));
}

TEST_F(MalformedFile, AbsurdPageSizes) {
  EXPECT_THAT(openError(withU32(valid_, kPageSizeAt, 0)),
              HasSubstr("header field page_size: 0 is not a power of two in [1, 4096]"));
  EXPECT_THAT(openError(withU32(valid_, kPageSizeAt, 12)),
              HasSubstr("header field page_size: 12 is not a power of two"));
  EXPECT_THAT(openError(withU32(valid_, kPageSizeAt, 1u << 31)),
              HasSubstr("header field page_size: 2147483648 is not a power of two in [1, 4096]"));
}

TEST_F(MalformedFile, AbsurdLevelCounts) {
  EXPECT_THAT(openError(withU32(valid_, kLevelCountAt, 40)),
              HasSubstr("header field level_count: 40 is outside [1, 16]"));
  EXPECT_THAT(openError(withU32(valid_, kLevelCountAt, 0)),
              HasSubstr("header field level_count: 0 is outside [1, 16]"));
}

TEST_F(MalformedFile, BorderNotSmallerThanThePage) {
  EXPECT_THAT(openError(withU32(valid_, kBorderAt, 8)),
              HasSubstr("header field border: 8 is not smaller than the page size 8"));
  EXPECT_THAT(openError(withU32(valid_, kBorderAt, 0xffffffffu)), HasSubstr("header field border"));
}

TEST_F(MalformedFile, UnknownTexelFormats) {
  EXPECT_THAT(openError(withU32(valid_, kChannelsAt, 0)),
              HasSubstr("header field channels: 0 is outside [1, 4]"));
  EXPECT_THAT(openError(withU32(valid_, kChannelsAt, 7)), HasSubstr("header field channels"));
  EXPECT_THAT(openError(withU32(valid_, kPixelFormatAt, 9)),
              HasSubstr("header field pixel_format: 9 is not a known pixel format"));
  EXPECT_THAT(openError(withU32(valid_, kColorSpaceAt, 5)),
              HasSubstr("header field color_space: 5"));
  EXPECT_THAT(openError(withU32(valid_, kFlagsAt, 6)),
              HasSubstr("header field flags: unknown bits set in 6"));
  EXPECT_THAT(openError(withU32(valid_, kReservedAt, 1)),
              HasSubstr("header field reserved: reserved bytes are not zero"));
}

TEST_F(MalformedFile, StoredPageCountOutsideTheTexture) {
  EXPECT_THAT(openError(withU64(valid_, kStoredPagesAt, 86)),
              HasSubstr("header field stored_page_count: 86 is outside [1, 85]"));
  EXPECT_THAT(openError(withU64(valid_, kStoredPagesAt, 0)),
              HasSubstr("header field stored_page_count: 0 is outside"));
  EXPECT_THAT(openError(withU64(withU32(valid_, kFlagsAt, 0), kStoredPagesAt, 13)),
              HasSubstr("header field stored_page_count: 13 is not the 85 pages of a dense"));
}

TEST_F(MalformedFile, SparseIndexOfTheWrongLength) {
  // One page fewer in the count than the index holds: the index no longer ends at noise_offset.
  EXPECT_THAT(openError(withU64(valid_, kStoredPagesAt, storedPages_ - 1)),
              HasSubstr("header field noise_offset: the sparse index between index_offset and "
                        "noise_offset is 104 bytes, 12 stored pages need 96"));
  EXPECT_THAT(openError(withU64(valid_, kNoiseOffsetAt, noiseOffset() - 8)),
              HasSubstr("header field noise_offset: the sparse index"));
}

TEST_F(MalformedFile, PageOffsetsPastTheEnd) {
  EXPECT_THAT(openError(withU64(valid_, kDataOffsetAt, valid_.size())),
              HasSubstr("header field data_offset: " + std::to_string(valid_.size()) + " is not " +
                        std::to_string(dataOffset())));
  EXPECT_THAT(openError(withU64(valid_, kDataOffsetAt, std::numeric_limits<uint64_t>::max())),
              HasSubstr("header field data_offset"));
  EXPECT_THAT(openError(withU64(valid_, kFileBytesAt, valid_.size() * 2)),
              HasSubstr("header field file_bytes"));
}

TEST_F(MalformedFile, CorruptedHeaderAndTables) {
  auto header = valid_;
  header[kTablesChecksumAt] ^= std::byte{1};  // without recomputing the header checksum
  EXPECT_THAT(openError(header), HasSubstr("header field header_checksum: does not match"));

  auto table = valid_;
  table[noiseOffset() + 5] ^= std::byte{0x10};
  EXPECT_THAT(openError(table), HasSubstr("header field tables_checksum: does not match"));
}

TEST_F(MalformedFile, SparseIndexThatBreaksItsRules) {
  auto falling = valid_;
  storeU64(falling.data() + kHeaderBytes + 8 * 2, 1);  // entry 2 equals entry 1
  EXPECT_THAT(openError(rehashTables(falling)),
              HasSubstr("sparse index: entry 2 (p_abs 1) does not rise above the entry before it"));

  auto orphan = valid_;
  const uint64_t last = kHeaderBytes + 8 * (storedPages_ - 1);
  storeU64(orphan.data() + last, 84);  // the last page of level 3, whose parent is not stored
  EXPECT_THAT(openError(rehashTables(orphan)),
              HasSubstr("is stored without its parent (p_abs 20)"));

  auto beyond = valid_;
  storeU64(beyond.data() + last, 85);
  EXPECT_THAT(openError(rehashTables(beyond)), HasSubstr("is beyond the texture's 85 pages"));

  auto rootless = valid_;
  storeU64(rootless.data() + kHeaderBytes, 2);
  EXPECT_THAT(openError(rehashTables(rootless)),
              HasSubstr("the root page (p_abs 0) is not stored"));
}

TEST_F(MalformedFile, NoiseValuesThatAreNotFiniteOrNegative) {
  for (const float bad : {std::nanf(""), std::numeric_limits<float>::infinity(), -0.5f}) {
    auto bytes = valid_;
    storeF32(bytes.data() + noiseOffset() + 4 * 3, bad);
    EXPECT_THAT(openError(rehashTables(bytes)), HasSubstr("NoiseValue table: entry 3 is"));
  }
}

TEST_F(MalformedFile, CorruptedPageIsDetectedWhenRead) {
  auto bytes = valid_;
  const uint64_t pageBytes = texture_.description.pageBytes();
  bytes[dataOffset() + 4 * pageBytes + 17] ^= std::byte{0x40};  // inside the 5th stored page
  test::writeBytes(dir_ / "corrupt.vt", bytes);
  const VirtualTextureReader reader(dir_ / "corrupt.vt");  // the tables are intact
  const PageId fifth = fromAbsoluteIndex(reader.storedPage(4));
  EXPECT_NO_THROW(reader.readPage(fromAbsoluteIndex(reader.storedPage(3))));
  EXPECT_THAT([&] { reader.readPage(fifth); },
              ::testing::ThrowsMessage<InputError>(HasSubstr(
                  "page 4 (level 1, x 1, y 1): checksum mismatch (the page data is corrupted)")));
}

TEST_F(MalformedFile, NotARegularFile) {
  EXPECT_THAT([&] { VirtualTextureReader reader(dir_.path()); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("not a regular file")));
  EXPECT_THAT(
      [&] { VirtualTextureReader reader(dir_ / "missing.vt"); },
      ::testing::ThrowsMessage<InputError>(HasSubstr("cannot open: No such file or directory")));
}

// Ancestor errors (version 3): the section after the pages, its flag, offset and checksum, and
// each row's values, all checked on open.
TEST_F(MalformedFile, AncestorErrorsThatBreakTheirRules) {
  texture_.ancestorErrors = true;
  writeSyntheticTexture(dir_ / "errors.vt", texture_);
  const std::vector<std::byte> valid = test::readBytes(dir_ / "errors.vt");
  const uint64_t offset = loadU64(valid.data() + kAncestorErrorOffsetAt);
  ASSERT_EQ(loadU32(valid.data() + kVersionAt), 3u);
  ASSERT_EQ(offset, valid_.size());  // the pages are where they were, the errors after them
  ASSERT_EQ(valid.size(), valid_.size() + 4 * 13 * 3);
  {
    const VirtualTextureReader reader(dir_ / "errors.vt");
    ASSERT_TRUE(reader.hasAncestorErrors());
    EXPECT_NE(reader.identity(), VirtualTextureReader(dir_ / "valid.vt").identity());
  }
  // The section's values patched, its checksum taken again.
  const auto withError = [&](uint64_t slot, uint32_t level, float value) {
    std::vector<std::byte> bytes = valid;
    storeF32(bytes.data() + offset + 4 * (slot * 3 + level), value);
    storeU64(bytes.data() + kAncestorErrorChecksumAt,
             checksum64(std::span<const std::byte>(bytes).subspan(offset)));
    return rehashHeader(std::move(bytes));
  };
  // Slot 12 is the last stored page of level 3 (stored pages 1 + 4 + 4 + 4).
  EXPECT_THAT(openError(withError(12, 1, 2.5f)),
              HasSubstr("ancestor errors: page 57 (level 3, x 4, y 4) holds"));
  EXPECT_THAT(openError(withError(12, 1, 2.5f)),
              HasSubstr("holds 2.500000 for level 1, not a value in [0, 2]"));
  EXPECT_THAT(openError(withError(12, 0, std::numeric_limits<float>::quiet_NaN())),
              HasSubstr("not a value in [0, 2]"));
  EXPECT_THAT(openError(withError(12, 2, -0.25f)), HasSubstr("not a value in [0, 2]"));
  // Slot 1 is on level 1: only its entry for level 0 may be set.
  EXPECT_THAT(openError(withError(1, 1, 0.5f)),
              HasSubstr("holds 0.500000 for level 1, no level above the page's (must be 0)"));
  // A value changed without its checksum.
  std::vector<std::byte> changed = valid;
  changed[offset + 5] ^= std::byte{1};
  EXPECT_THAT(openError(changed),
              HasSubstr("header field ancestor_error_checksum: does not match the ancestor errors"));
  // The flag in an older version, the section without the flag, and a wrong offset.
  EXPECT_THAT(openError(withU32(valid, kVersionAt, 2)),
              HasSubstr("header field flags: bit 1 (ancestor errors) needs version 3, the file "
                        "is version 2"));
  EXPECT_THAT(openError(withU32(valid_, kFlagsAt, kFlagSparse | kFlagAncestorErrors)),
              HasSubstr("needs version 3, the file is version 1"));
  EXPECT_THAT(openError(withU32(valid, kFlagsAt, kFlagSparse)),
              HasSubstr("header field ancestor_error_offset: " + std::to_string(offset) +
                        " is not 0 (the flags name no ancestor errors)"));
  EXPECT_THAT(openError(withU64(valid, kAncestorErrorOffsetAt, offset - 4)),
              HasSubstr("is not " + std::to_string(offset) + " (after 13 pages)"));
  EXPECT_THAT(openError(withU64(valid_, kAncestorErrorChecksumAt, 1)),
              HasSubstr("header field ancestor_error_checksum: is not zero, and the flags name "
                        "no ancestor errors"));
  // Cut inside the section.
  EXPECT_THAT(openError({valid.begin(), valid.end() - 4}),
              HasSubstr("truncated: the header declares " + std::to_string(valid.size())));
}

}  // namespace
}  // namespace vt
