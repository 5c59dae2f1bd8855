#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "build/synthetic_texture.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "format/block_compression.h"
#include "format/file_header.h"
#include "format/level_image.h"
#include "format/virtual_texture_reader.h"
#include "format/virtual_texture_writer.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TextureDescription smallDescription() {
  return {.pageSize = 16, .border = 2, .levelCount = 4, .channels = 4};
}

// Writes every page of `texture` in the order given.
void writePages(VirtualTextureWriter& writer, const TextureDescription& d,
                const std::vector<uint64_t>& order) {
  for (const uint64_t p : order) {
    const PageId page = fromAbsoluteIndex(p);
    writer.writePage(page, syntheticPage(d, page), 0.01f * static_cast<float>(p % 7));
  }
}

TEST(VirtualTextureFile, DenseRoundTripGivesBackEveryPageAndItsNoiseValue) {
  test::ScratchDirectory dir;
  const SyntheticTexture texture{smallDescription(), std::nullopt};
  writeSyntheticTexture(dir / "dense.vt", texture);

  const VirtualTextureReader reader(dir / "dense.vt");
  EXPECT_EQ(reader.description(), texture.description);
  EXPECT_FALSE(reader.isSparse());
  EXPECT_EQ(reader.storedPageCount(), 85u);  // 1 + 4 + 16 + 64
  EXPECT_EQ(reader.storedPagesPerLevel(), (std::vector<uint64_t>{1, 4, 16, 64}));
  EXPECT_EQ(reader.fileBytes(), 128u + 85u * (4 + 8) + 85u * 20 * 20 * 4);
  for (uint64_t p = 0; p < reader.storedPageCount(); ++p) {
    const PageId page = fromAbsoluteIndex(p);
    ASSERT_EQ(reader.readPage(page), syntheticPage(texture.description, page)) << p;
    if (page.level > 0) {
      EXPECT_GT(reader.noiseValue(page), 0.0f) << p;
    }
  }
  EXPECT_EQ(reader.noiseValue(PageId{}), 0.0f);
}

TEST(VirtualTextureFile, SparseTextureStoresOnlyItsPagesAndTheirAncestors) {
  test::ScratchDirectory dir;
  const SyntheticTexture texture{smallDescription(), 0.2};
  writeSyntheticTexture(dir / "sparse.vt", texture);

  const VirtualTextureReader reader(dir / "sparse.vt");
  EXPECT_TRUE(reader.isSparse());
  const std::vector<uint64_t> stored = syntheticStoredPages(texture);
  ASSERT_EQ(reader.storedPageCount(), stored.size());
  EXPECT_LT(stored.size(), texture.description.totalPages());
  // A disc of radius 0.2 around the centre touches the 2 x 2 central pages of level 2 (pages
  // 0.25 wide) and the 4 x 4 central pages of level 3 (0.125 wide).
  EXPECT_EQ(reader.storedPagesPerLevel(), (std::vector<uint64_t>{1, 4, 4, 16}));
  EXPECT_TRUE(reader.contains(PageId{3, 3, 3}));
  EXPECT_FALSE(reader.contains(PageId{0, 0, 3}));
  EXPECT_FALSE(reader.contains(PageId{0, 0, 4}));  // beyond the finest level
  for (uint64_t slot = 0; slot < stored.size(); ++slot) {
    ASSERT_EQ(reader.storedPage(slot), stored[slot]);
    const PageId page = fromAbsoluteIndex(stored[slot]);
    ASSERT_EQ(reader.readPage(page), syntheticPage(texture.description, page));
  }
  EXPECT_THAT(
      [&] {
        reader.readPage(PageId{0, 0, 3});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("is not stored in this texture")));
  // Absent pages store no bytes.
  EXPECT_EQ(std::filesystem::file_size(dir / "sparse.vt"),
            128u + stored.size() * (8 + 4 + 8 + texture.description.pageBytes()));
}

// A block format stores each page's blocks (8 or 16 bytes per 4 x 4 texels) and reads back the
// decoded blocks; an unorm8 file stays version 1.
TEST(VirtualTextureFile, BlockFormatsStoreBlocksAndReadBackTheirDecodedTexels) {
  test::ScratchDirectory dir;
  for (const PixelFormat format : {PixelFormat::kBc1, PixelFormat::kBc3}) {
    TextureDescription d = smallDescription();
    d.format = format;
    writeSyntheticTexture(dir / "blocks.vt", {d, std::nullopt});
    const VirtualTextureReader reader(dir / "blocks.vt");
    EXPECT_EQ(reader.description(), d);
    const uint64_t blockBytes = format == PixelFormat::kBc1 ? 8 : 16;
    EXPECT_EQ(d.storedPageBytes(), 5u * 5u * blockBytes);  // 20 x 20 texels: 5 x 5 blocks
    EXPECT_EQ(reader.fileBytes(), 128u + 85u * (4 + 8) + 85u * d.storedPageBytes());
    EXPECT_EQ(loadU32(test::readBytes(dir / "blocks.vt").data() + 8), 2u);  // version
    size_t differing = 0;
    for (uint64_t p = 0; p < reader.storedPageCount(); ++p) {
      const PageId page = fromAbsoluteIndex(p);
      std::vector<std::byte> texels = syntheticPage(d, page), blocks(d.storedPageBytes()),
                             decoded(d.pageBytes()), stored(d.storedPageBytes());
      encodeBlocks(format, d.storedPageSide(), texels, blocks);
      decodeBlocks(format, d.storedPageSide(), blocks, decoded);
      reader.readStoredPage(page, stored);
      ASSERT_EQ(stored, blocks) << p;
      ASSERT_EQ(reader.readPage(page), decoded) << p;
      for (size_t i = 0; i < texels.size(); ++i) {
        // BC1 is opaque; otherwise within the encoding's error of the synthetic texels.
        const int want =
            format == PixelFormat::kBc1 && i % 4 == 3 ? 255 : static_cast<int>(texels[i]);
        const int error = std::abs(static_cast<int>(decoded[i]) - want);
        ASSERT_LE(error, 128) << p << ", byte " << i;
        differing += error > 0;
      }
    }
    EXPECT_GT(differing, 0u);  // a lossy encoding: the test would notice texels stored as such
  }
  writeSyntheticTexture(dir / "plain.vt", {smallDescription(), std::nullopt});
  EXPECT_EQ(loadU32(test::readBytes(dir / "plain.vt").data() + 8), 1u);
}

TEST(VirtualTextureFile, BytesDoNotDependOnWriteOrderOrThreads) {
  test::ScratchDirectory dir;
  for (const PixelFormat format : {PixelFormat::kUnorm8, PixelFormat::kBc1}) {
    TextureDescription d = smallDescription();
    d.format = format;
    std::vector<uint64_t> order(d.totalPages());
    for (uint64_t p = 0; p < order.size(); ++p) order[p] = p;
    {
      VirtualTextureWriter writer(dir / "forward.vt", d);
      writePages(writer, d, order);
      writer.commit();
    }
    {
      std::reverse(order.begin(), order.end());
      VirtualTextureWriter writer(dir / "backward.vt", d);
      writePages(writer, d, order);
      writer.commit();
    }
    {
      VirtualTextureWriter writer(dir / "threads.vt", d);
      std::vector<std::thread> threads;
      for (uint64_t t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
          std::vector<uint64_t> mine;
          for (uint64_t p = t; p < d.totalPages(); p += 4) mine.push_back(p);
          writePages(writer, d, mine);
        });
      for (auto& thread : threads) thread.join();
      writer.commit();
    }
    const auto forward = test::readBytes(dir / "forward.vt");
    EXPECT_EQ(forward, test::readBytes(dir / "backward.vt"));
    EXPECT_EQ(forward, test::readBytes(dir / "threads.vt"));
  }
}

TEST(VirtualTextureFile, ConcurrentReadsReturnTheSamePages) {
  test::ScratchDirectory dir;
  const SyntheticTexture texture{smallDescription(), std::nullopt};
  writeSyntheticTexture(dir / "t.vt", texture);
  const VirtualTextureReader reader(dir / "t.vt");
  std::vector<int> mismatches(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int round = 0; round < 5; ++round)
        for (uint64_t p = 0; p < reader.storedPageCount(); ++p) {
          const PageId page = fromAbsoluteIndex((p * 7 + static_cast<uint64_t>(t)) % 85);
          mismatches[static_cast<size_t>(t)] +=
              reader.readPage(page) != syntheticPage(texture.description, page);
        }
    });
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(mismatches, std::vector<int>(4, 0));
}

TEST(VirtualTextureFile, UncommittedWriterLeavesNothingAndKeepsThePreviousFile) {
  test::ScratchDirectory dir;
  const TextureDescription d = smallDescription();
  writeSyntheticTexture(dir / "t.vt", SyntheticTexture{d, std::nullopt});
  const auto before = test::readBytes(dir / "t.vt");
  {
    VirtualTextureWriter writer(dir / "t.vt", d);
    writer.writePage(PageId{}, syntheticPage(d, PageId{}), 0.0f);
    EXPECT_THAT([&] { writer.commit(); }, ::testing::ThrowsMessage<InputError>(HasSubstr(
                                              "84 pages were never written, the first is page 1")));
  }
  EXPECT_EQ(test::readBytes(dir / "t.vt"), before);
  // No temporary file is left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(VirtualTextureFile, WriterRejectsMisuse) {
  test::ScratchDirectory dir;
  const TextureDescription d = smallDescription();
  VirtualTextureWriter writer(dir / "t.vt", d);
  const auto root = syntheticPage(d, PageId{});
  writer.writePage(PageId{}, root, 0.0f);
  EXPECT_THROW(writer.writePage(PageId{}, root, 0.0f), std::invalid_argument);  // twice
  EXPECT_THROW(writer.writePage(PageId{0, 0, 4}, root, 0.0f), std::invalid_argument);
  EXPECT_THROW(writer.writePage(PageId{1, 0, 1}, std::span(root).first(10), 0.0f),
               std::invalid_argument);
  EXPECT_THROW(writer.writePage(PageId{1, 0, 1}, root, std::nanf("")), std::invalid_argument);
  EXPECT_THROW(writer.writePage(PageId{1, 0, 1}, root, -1.0f), std::invalid_argument);

  EXPECT_THAT(
      [&] {
        VirtualTextureWriter(dir / "bad.vt", d, {0, 2, 1});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("does not rise")));
  EXPECT_THAT(
      [&] {
        VirtualTextureWriter(dir / "bad.vt", d, {0, 5});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("without its parent (p_abs 1)")));
  EXPECT_THAT([&] { VirtualTextureWriter(dir / "bad.vt", d, {1}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("root page")));
  TextureDescription badBorder = d;
  badBorder.border = 16;
  EXPECT_THAT([&] { VirtualTextureWriter(dir / "bad.vt", badBorder); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("border 16 is not smaller")));
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.vt"));
}

TEST(VirtualTextureFile, AssembledLevelDropsBordersAndLeavesAbsentPagesBlack) {
  test::ScratchDirectory dir;
  const TextureDescription d = smallDescription();
  writeSyntheticTexture(dir / "t.vt", SyntheticTexture{d, 0.2});
  const VirtualTextureReader reader(dir / "t.vt");
  const LevelImage image = assembleLevel(reader, 3);
  ASSERT_EQ(image.side, 128u);
  const auto texel = [&](uint32_t x, uint32_t y, uint32_t c) {
    return std::to_integer<int>(image.texels[(size_t{y} * image.side + x) * 4 + c]);
  };
  // Page (3, 3) of level 3 is stored: its interior texel (5, 7) is the page's texel (5 + B, 7 + B).
  const auto page = syntheticPage(d, PageId{3, 3, 3});
  for (uint32_t c = 0; c < 4; ++c)
    EXPECT_EQ(texel(3 * 16 + 5, 3 * 16 + 7, c),
              std::to_integer<int>(page[((7 + 2) * 20 + (5 + 2)) * 4 + c]));
  // Page (0, 0) of level 3 is not stored.
  EXPECT_EQ(texel(1, 1, 3), 0);
  EXPECT_THROW(assembleLevel(reader, 4), InputError);
}

}  // namespace
}  // namespace vt
