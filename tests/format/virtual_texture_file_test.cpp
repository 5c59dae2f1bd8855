#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "build/block_encoding.h"
#include "build/synthetic_texture.h"
#include "common/error.h"
#include "common/little_endian.h"
#include "format/block_decoding.h"
#include "format/file_header.h"
#include "format/level_image.h"
#include "format/virtual_texture_reader.h"
#include "format/virtual_texture_writer.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

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
      VirtualTextureWriter writer(dir / "forward.vt", d, BlockEncoder(encodeBlocks));
      writePages(writer, d, order);
      writer.commit();
    }
    {
      std::reverse(order.begin(), order.end());
      VirtualTextureWriter writer(dir / "backward.vt", d, BlockEncoder(encodeBlocks));
      writePages(writer, d, order);
      writer.commit();
    }
    {
      VirtualTextureWriter writer(dir / "threads.vt", d, BlockEncoder(encodeBlocks));
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

// The decoding of format/block_decoding.h on blocks worked out by hand.
TEST(VirtualTextureFile, BlocksDecodeAsTheSpecificationWithThirdsRoundedToNearest) {
  const auto decodeOne = [](PixelFormat format, std::vector<uint8_t> block) {
    std::vector<std::byte> bytes(block.size()), texels(4 * 4 * 4);
    for (size_t k = 0; k < block.size(); ++k) bytes[k] = std::byte{block[k]};
    decodeBlocks(format, 4, bytes, texels);
    std::vector<int> values;
    for (const std::byte b : texels) values.push_back(static_cast<int>(b));
    return values;
  };
  const auto texel = [](const std::vector<int>& t, int k) {
    return std::vector<int>(t.begin() + 4 * k, t.begin() + 4 * k + 4);
  };
  // BC1, c0 = 0xF800 (red 31 -> 255) > c1 = 0x001F (blue 31 -> 255): four colours. Texel k takes
  // index k % 4: red, blue, round(2/3 255) = 170 red + 85 blue, and the reverse.
  const auto four = decodeOne(PixelFormat::kBc1, {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xE4, 0xE4, 0xE4});
  EXPECT_EQ(texel(four, 0), (std::vector<int>{255, 0, 0, 255}));
  EXPECT_EQ(texel(four, 1), (std::vector<int>{0, 0, 255, 255}));
  EXPECT_EQ(texel(four, 2), (std::vector<int>{170, 0, 85, 255}));
  EXPECT_EQ(texel(four, 3), (std::vector<int>{85, 0, 170, 255}));
  // c0 = 0x0841 (1, 2, 1 -> 8, 8, 8) <= c1 = 0x1082 (2, 4, 2 -> 16, 16, 16): three colours, the
  // half way 12 and black, opaque.
  const auto three = decodeOne(PixelFormat::kBc1, {0x41, 0x08, 0x82, 0x10, 0xE4, 0xE4, 0xE4, 0xE4});
  EXPECT_EQ(texel(three, 0), (std::vector<int>{8, 8, 8, 255}));
  EXPECT_EQ(texel(three, 2), (std::vector<int>{12, 12, 12, 255}));
  EXPECT_EQ(texel(three, 3), (std::vector<int>{0, 0, 0, 255}));
  // BC3: alpha 200 > 100, eight values (index i of texel i % 8: 200, 100, round((6 * 200 +
  // 100) / 7) = 186 (185.7), ..., round((200 + 6 * 100) / 7) = 114 (114.3)); its colour block is
  // the first BC1 block, four colours although c0 > c1 does not matter for BC3.
  // Indices 0..7 repeated: bits 000 001 010 011 100 101 110 111 = 0x88 0xC6 0xFA twice.
  const auto eight = decodeOne(PixelFormat::kBc3, {200, 100, 0x88, 0xC6, 0xFA, 0x88, 0xC6, 0xFA,
                                                   0x41, 0x08, 0x82, 0x10, 0xE4, 0xE4, 0xE4, 0xE4});
  const std::vector<int> alphas = {200, 100, 186, 171, 157, 143, 129, 114};
  for (int k = 0; k < 16; ++k) EXPECT_EQ(texel(eight, k)[3], alphas[k % 8]) << k;
  EXPECT_EQ(texel(eight, 2), (std::vector<int>{11, 11, 11, 186}));  // round((16 + 16) / 3) = 11
  // Alpha 100 <= 200: six values, then 0 and 255.
  const auto six = decodeOne(PixelFormat::kBc3, {100, 200, 0x88, 0xC6, 0xFA, 0x88, 0xC6, 0xFA, 0x41,
                                                 0x08, 0x82, 0x10, 0xE4, 0xE4, 0xE4, 0xE4});
  const std::vector<int> sixAlphas = {100, 200, 120, 140, 160, 180, 0, 255};
  for (int k = 0; k < 16; ++k) EXPECT_EQ(texel(six, k)[3], sixAlphas[k % 8]) << k;
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
  TextureDescription blocks = d;
  blocks.format = PixelFormat::kBc3;
  EXPECT_THAT([&] { VirtualTextureWriter(dir / "bc3.vt", blocks); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("pixel format bc3 needs a block encoder")));

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
  EXPECT_THAT([&] { assembleLevel(reader, 4); },
              ThrowsMessage<InputError>((dir / "t.vt").string() +
                                        ": level 4 does not exist (levels 0..3)"));
}

}  // namespace
}  // namespace vt
