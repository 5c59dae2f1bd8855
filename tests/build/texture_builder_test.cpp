// vt build against an independent, naive computation: the whole mip chain in memory, pages cut by
// hand. The builder streams rows through rings; the naive chain holds every level whole.

#include "build/texture_builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "build/ancestor_error.h"
#include "build/mip_kernel.h"
#include "build/noise_value.h"
#include "common/error.h"
#include "common/image_file.h"
#include "format/virtual_texture_reader.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

struct Level {
  uint64_t side = 0;
  std::vector<uint8_t> texels;
};

// The naive chain: the finest level composed from `images` (same channel count as the texture),
// each coarser level from the whole level above, texel by texel.
std::vector<Level> naiveChain(const Layout& layout,
                              const std::vector<std::vector<uint8_t>>& images) {
  const TextureDescription& d = layout.description;
  const uint32_t c = d.channels;
  std::vector<Level> chain(d.levelCount);
  Level& finest = chain.back();
  finest.side = d.sideTexels();
  finest.texels.resize(finest.side * finest.side * c);
  for (uint64_t t = 0; t < finest.side * finest.side; ++t)
    for (uint32_t k = 0; k < c; ++k) finest.texels[t * c + k] = layout.background[k];
  for (size_t i = 0; i < images.size(); ++i) {
    const Placement& p = layout.images[i];
    for (uint32_t y = 0; y < p.height; ++y)
      for (uint32_t x = 0; x < p.width * c; ++x)
        finest.texels[((p.y + y) * finest.side + p.x) * c + x] = images[i][y * p.width * c + x];
  }
  const MipKernel kernel(layout.filter, d.colorSpace, c);
  for (uint32_t m = d.finestLevel(); m-- > 0;) {
    const Level& above = chain[m + 1];
    Level& level = chain[m];
    level.side = above.side / 2;
    level.texels.resize(level.side * level.side * c);
    for (uint64_t Y = 0; Y < level.side; ++Y) {
      MipKernel::Rows rows{};
      for (uint32_t k = 0; k < 2 + 2 * kernel.reach(); ++k) {
        const int64_t row = std::clamp<int64_t>(static_cast<int64_t>(2 * Y + k) - kernel.reach(), 0,
                                                static_cast<int64_t>(above.side) - 1);
        rows[k] = above.texels.data() + static_cast<uint64_t>(row) * above.side * c;
      }
      for (uint64_t X = 0; X < level.side; ++X)
        kernel.texel(rows, X, above.side, level.texels.data() + (Y * level.side + X) * c);
    }
  }
  return chain;
}

// A stored page cut by hand: texel (px P - B + i, py P - B + j), clamped to the level.
std::vector<std::byte> naivePage(const TextureDescription& d, const Level& level, PageId page) {
  const uint32_t side = d.storedPageSide(), c = d.channels;
  std::vector<std::byte> texels(d.pageBytes());
  for (uint32_t j = 0; j < side; ++j)
    for (uint32_t i = 0; i < side; ++i) {
      const auto clamp = [&](int64_t v) {
        return static_cast<uint64_t>(
            std::clamp<int64_t>(v, 0, static_cast<int64_t>(level.side) - 1));
      };
      const uint64_t x = clamp(int64_t{page.x} * d.pageSize - d.border + i);
      const uint64_t y = clamp(int64_t{page.y} * d.pageSize - d.border + j);
      for (uint32_t k = 0; k < c; ++k)
        texels[(size_t{j} * side + i) * c + k] =
            std::byte(level.texels[(y * level.side + x) * c + k]);
    }
  return texels;
}

// A deterministic image with detail at every scale.
std::vector<uint8_t> detailedPattern(uint32_t width, uint32_t height, uint32_t channels,
                                     uint32_t seed) {
  std::vector<uint8_t> texels(size_t{width} * height * channels);
  uint32_t state = seed * 2654435761u + 1;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (uint32_t k = 0; k < channels; ++k) {
        state = state * 1664525u + 1013904223u;
        const uint32_t smooth = (x * 7 + y * 3 + k * 50) % 256;
        texels[(size_t{y} * width + x) * channels + k] =
            static_cast<uint8_t>((smooth + ((state >> 24) % 64)) % 256);
      }
  return texels;
}

class TextureBuilder : public ::testing::Test {
 protected:
  // Writes the images as PNG and a layout naming them; returns the layout file.
  std::filesystem::path writeLayout(const nlohmann::json& settings,
                                    const std::vector<std::array<uint32_t, 4>>& placements,
                                    uint32_t channels) {
    nlohmann::json layout = settings;
    layout["images"] = nlohmann::json::array();
    images_.clear();
    for (size_t i = 0; i < placements.size(); ++i) {
      const auto [x, y, w, h] = placements[i];
      images_.push_back(detailedPattern(w, h, channels, static_cast<uint32_t>(i)));
      const std::string name = "image" + std::to_string(i) + ".png";
      writeImage8(dir_ / name, w, h, channels,
                  std::as_bytes(std::span(images_.back().data(), images_.back().size())));
      layout["images"].push_back({{"file", name}, {"x", x}, {"y", y}});
    }
    std::ofstream(dir_ / "layout.json") << layout.dump(2);
    return dir_ / "layout.json";
  }

  // Builds the layout and checks every stored page and NoiseValue against the naive chain.
  void expectMatchesNaive(const std::filesystem::path& layoutFile, unsigned threads) {
    const Layout layout = readLayout(layoutFile);
    const auto output = dir_ / "built.vt";
    const BuildReport report = buildVirtualTexture(layout, output, {threads, false});
    const auto chain = naiveChain(layout, images_);
    const VirtualTextureReader reader(output);
    const TextureDescription& d = reader.description();
    EXPECT_EQ(d, layout.description);
    EXPECT_EQ(reader.storedPageCount(), report.storedPages);
    for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot) {
      const PageId page = fromAbsoluteIndex(reader.storedPage(slot));
      const auto expected = naivePage(d, chain[page.level], page);
      ASSERT_EQ(reader.readPage(page), expected) << "page " << absoluteIndex(page);
      const float noise =
          page.level == 0
              ? 0.0f
              : noiseValue(d, page, expected, naivePage(d, chain[page.level - 1], parent(page)));
      ASSERT_EQ(reader.noiseValue(page), noise) << "page " << absoluteIndex(page);
    }
  }

  test::ScratchDirectory dir_;
  std::vector<std::vector<uint8_t>> images_;
};

TEST_F(TextureBuilder, DenseLinearBoxMatchesTheNaiveChain) {
  const auto layout = writeLayout({{"page_size", 16}, {"border", 2}, {"color_space", "linear"}},
                                  {{0, 0, 128, 70}, {0, 70, 128, 58}}, 3);
  expectMatchesNaive(layout, 2);
  EXPECT_FALSE(VirtualTextureReader(dir_ / "built.vt").isSparse());
}

TEST_F(TextureBuilder, SrgbTentWithWideBorderMatchesTheNaiveChain) {
  const auto layout =
      writeLayout({{"page_size", 8}, {"border", 3}, {"filter", "tent"}, {"color_space", "srgb"}},
                  {{0, 0, 64, 64}}, 4);
  expectMatchesNaive(layout, 2);
}

TEST_F(TextureBuilder, SparseLayoutStoresOnlyTouchedPages) {
  const auto layout = writeLayout(
      {{"page_size", 16}, {"border", 1}, {"side", 256}, {"background", {10, 20, 30, 255}}},
      {{3, 5, 20, 9}, {200, 180, 40, 30}}, 4);
  expectMatchesNaive(layout, 2);
  const VirtualTextureReader reader(dir_ / "built.vt");
  EXPECT_TRUE(reader.isSparse());
  // Finest level (16 x 16 pages of 16 texels): image 0 touches pages x 0..1, y 0;
  // image 1 (200..239, 180..209) touches x 12..14, y 11..13.
  EXPECT_EQ(reader.storedPagesPerLevel().back(), 2u + 9u);
  EXPECT_TRUE(reader.contains(PageId{1, 0, 4}));
  EXPECT_FALSE(reader.contains(PageId{2, 0, 4}));
  EXPECT_TRUE(reader.contains(PageId{14, 13, 4}));
  EXPECT_FALSE(reader.contains(PageId{5, 5, 4}));
  const std::string refusal =
      (dir_ / "built.vt").string() + ": page 170 (level 4, x 5, y 5) is not stored in this texture";
  EXPECT_THAT([&] { reader.readPage(PageId{5, 5, 4}); }, ThrowsMessage<InputError>(refusal));
}

TEST_F(TextureBuilder, SparseTentSkipsOnlyBackgroundTexels) {
  // The builder computes only texels some image influences (footprints widened by the tent's
  // reach on every level); the naive chain computes them all. Images at the texture's edges and
  // odd positions test the widening and the clamping.
  const auto layout = writeLayout({{"page_size", 8},
                                   {"border", 2},
                                   {"side", 256},
                                   {"filter", "tent"},
                                   {"background", {200, 30, 60, 128}}},
                                  {{0, 0, 5, 3}, {97, 131, 11, 7}, {251, 250, 5, 6}}, 4);
  expectMatchesNaive(layout, 2);
}

TEST_F(TextureBuilder, StripsAcrossColumnsRetiredAndReusedMatchTheNaiveChain) {
  // The rings hold 256-column strips (row_ring.h). Images straddling strip boundaries on every
  // level, with the tent's reach reading across them; strips made for the upper images are
  // retired and reused, from the pool, for other columns further down.
  const auto layout = writeLayout({{"page_size", 16},
                                   {"border", 2},
                                   {"side", 1024},
                                   {"filter", "tent"},
                                   {"background", {17, 200, 90, 40}}},
                                  {{250, 10, 20, 30},
                                   {500, 300, 30, 8},
                                   {700, 600, 300, 40},
                                   {0, 1000, 1024, 24}},
                                  4);
  expectMatchesNaive(layout, 2);
}

TEST_F(TextureBuilder, RingsOfASmallImagePlacedFarOutFollowTheImageNotTheWidth) {
  // A 1 x 1 image at the far corner of a 2^22-texel-wide texture: rings as wide as the texture
  // would hold 138 rows of 2^22 RGB texels per level, 3.5 GB; strips hold one 256-column strip
  // per level.
  const auto layoutFile =
      writeLayout({{"side", 4194304}}, {{4194303, 4194303, 1, 1}}, 3);
  const Layout layout = readLayout(layoutFile);
  EXPECT_LT(ringBytesBound(layout), uint64_t{4} << 20);
  const BuildReport report = buildVirtualTexture(layout, dir_ / "far.vt", {2, false});
  EXPECT_LE(report.ringBytes, ringBytesBound(layout));
  const VirtualTextureReader reader(dir_ / "far.vt");
  EXPECT_EQ(reader.storedPageCount(), layout.description.levelCount);  // one page per level
  const PageId corner{32767, 32767, layout.description.finestLevel()};
  const std::vector<std::byte> page = reader.readPage(corner);
  // The image's texel at the page's inner corner (texel P - 1 + B of its stored rows and columns).
  const uint32_t side = layout.description.storedPageSide(), at = side - 1 - layout.description.border;
  for (uint32_t k = 0; k < 3; ++k)
    EXPECT_EQ(page[(size_t{at} * side + at) * 3 + k], std::byte(images_[0][k]));
}

TEST_F(TextureBuilder, OutputBytesDoNotDependOnThreads) {
  const auto layout = writeLayout({{"page_size", 16}, {"border", 4}}, {{0, 0, 100, 128}}, 3);
  const Layout parsed = readLayout(layout);
  buildVirtualTexture(parsed, dir_ / "one.vt", {1, false});
  buildVirtualTexture(parsed, dir_ / "two.vt", {2, false});
  buildVirtualTexture(parsed, dir_ / "eight.vt", {8, false});
  const auto one = test::readBytes(dir_ / "one.vt");
  EXPECT_EQ(one, test::readBytes(dir_ / "two.vt"));
  EXPECT_EQ(one, test::readBytes(dir_ / "eight.vt"));
}

// `vt build --ancestor-errors`: the pages as without, the table after them (version 3) the same
// for any thread count, each entry the page's error through that ancestor as the pages read back
// give it, and coarser ancestors worse on the whole (each level of the image adds detail).
TEST_F(TextureBuilder, AncestorErrorsMeasureThePagesReadBackAndDoNotDependOnThreads) {
  const auto layout = writeLayout({{"page_size", 16}, {"border", 4}}, {{0, 0, 100, 128}}, 3);
  const Layout parsed = readLayout(layout);
  buildVirtualTexture(parsed, dir_ / "plain.vt", {2, false});
  buildVirtualTexture(parsed, dir_ / "one.vt", {1, false, 0, true});
  const BuildReport report = buildVirtualTexture(parsed, dir_ / "two.vt", {2, false, 0, true});
  EXPECT_GT(report.ancestorErrorSeconds, 0.0);
  const auto one = test::readBytes(dir_ / "one.vt"), plain = test::readBytes(dir_ / "plain.vt");
  EXPECT_EQ(one, test::readBytes(dir_ / "two.vt"));
  // Past the header, the file without them is the start of the file with them.
  ASSERT_GT(one.size(), plain.size());
  EXPECT_TRUE(std::equal(plain.begin() + kHeaderBytes, plain.end(), one.begin() + kHeaderBytes));

  const VirtualTextureReader reader(dir_ / "two.vt");
  ASSERT_TRUE(reader.hasAncestorErrors());
  const TextureDescription& d = reader.description();
  std::vector<double> sum(d.levelCount, 0.0);
  std::vector<int> count(d.levelCount, 0);
  for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot) {
    const PageId page = fromAbsoluteIndex(reader.storedPage(slot));
    const std::span<const float> errors = reader.ancestorErrors(page);
    ASSERT_EQ(errors.size(), page.level);
    const std::vector<float> own = pageLuminance(d, reader.readPage(page));
    for (uint32_t l = 0; l < page.level; ++l) {
      const std::vector<float> up = pageLuminance(d, reader.readPage(ancestorAt(page, l)));
      EXPECT_EQ(errors[l], ancestorError(d, page, own, l, up));
      sum[page.level - l] += errors[l];
      ++count[page.level - l];
    }
  }
  for (uint32_t up = 2; up < d.levelCount; ++up)
    EXPECT_GT(sum[up] / count[up], sum[up - 1] / count[up - 1]) << up << " levels up";
  EXPECT_GT(sum[1] / count[1], 0.01);
}

TEST_F(TextureBuilder, BordersHoldTheNeighboursTexelsAndClampAtTheEdge) {
  const auto layout = writeLayout({{"page_size", 8}, {"border", 2}, {"color_space", "linear"}},
                                  {{0, 0, 32, 32}}, 1);
  const Layout parsed = readLayout(layout);
  buildVirtualTexture(parsed, dir_ / "b.vt", {2, false});
  const VirtualTextureReader reader(dir_ / "b.vt");
  const auto left = reader.readPage(PageId{0, 0, 2}), right = reader.readPage(PageId{1, 0, 2});
  const auto at = [](const std::vector<std::byte>& page, int i, int j) {
    return std::to_integer<int>(page[static_cast<size_t>(j * 12 + i)]);
  };
  const auto image = [&](int x, int y) { return int{images_[0][static_cast<size_t>(y * 32 + x)]}; };
  for (int j = 2; j < 10; ++j) {
    // The right page's left border (stored columns 0, 1) is the left page's columns 6, 7.
    EXPECT_EQ(at(right, 0, j), at(left, 8, j));
    EXPECT_EQ(at(right, 1, j), at(left, 9, j));
    EXPECT_EQ(at(right, 0, j), image(6, j - 2));
    // The left page's left border repeats the texture's column 0.
    EXPECT_EQ(at(left, 0, j), image(0, j - 2));
    EXPECT_EQ(at(left, 1, j), image(0, j - 2));
  }
  // Top border of the top row of pages repeats row 0.
  for (int i = 2; i < 10; ++i) EXPECT_EQ(at(left, i, 0), image(i - 2, 0));
}

TEST_F(TextureBuilder, ConstantTextureHasNoNoise) {
  const std::vector<uint8_t> gray(64 * 64, 90);
  writeImage8(dir_ / "gray.png", 64, 64, 1, std::as_bytes(std::span(gray)));
  const Layout layout = singleImageLayout(dir_ / "gray.png", {.pageSize = 8, .border = 1});
  buildVirtualTexture(layout, dir_ / "c.vt", {2, false});
  const VirtualTextureReader reader(dir_ / "c.vt");
  EXPECT_EQ(reader.storedPageCount(), 85u);
  for (const float noise : reader.noiseValues()) EXPECT_EQ(noise, 0.0f);
}

TEST_F(TextureBuilder, StripesHaveTheirHandComputedNoiseValue) {
  // One-texel stripes 0, 255, 0, 255 (linear): every coarser texel is (0 + 255 + 0 + 255) / 4 =
  // 127.5 -> 128. A finest page differs from its upsampled parent by 128 or 127 (of 255) on half
  // of its texels each: RMSE = sqrt((128^2 + 127^2) / 2) / 255. Coarser pages are flat: 0.
  std::vector<uint8_t> stripes(64 * 64);
  for (size_t t = 0; t < stripes.size(); ++t) stripes[t] = (t % 2) ? 255 : 0;
  writeImage8(dir_ / "stripes.png", 64, 64, 1, std::as_bytes(std::span(stripes)));
  const Layout layout = singleImageLayout(
      dir_ / "stripes.png", {.pageSize = 16, .border = 1, .colorSpace = ColorSpace::kLinear});
  buildVirtualTexture(layout, dir_ / "s.vt", {2, false});
  const VirtualTextureReader reader(dir_ / "s.vt");
  const float expected =
      static_cast<float>(std::sqrt((128.0 * 128.0 + 127.0 * 127.0) / 2.0) / 255.0);
  for (uint64_t p = 0; p < reader.storedPageCount(); ++p) {
    const PageId page = fromAbsoluteIndex(p);
    if (page.level == 2)
      EXPECT_NEAR(reader.noiseValue(page), expected, 1e-6f) << p;
    else
      EXPECT_EQ(reader.noiseValue(page), 0.0f) << p;
  }
}

TEST_F(TextureBuilder, RingsStayWithinTheDocumentedBoundFarBelowTheFinestLevel) {
  // A 4096^2 RGBA texture (64 MiB finest level) from one small image.
  const auto layout =
      writeLayout({{"page_size", 64}, {"border", 4}, {"side", 4096}}, {{1000, 3000, 50, 40}}, 4);
  const Layout parsed = readLayout(layout);
  const BuildReport report = buildVirtualTexture(parsed, dir_ / "big.vt", {2, false});
  const uint64_t finestBytes = uint64_t{4096} * 4096 * 4;
  EXPECT_LE(report.ringBytes, ringBytesBound(parsed));
  EXPECT_LT(ringBytesBound(parsed), finestBytes / 16);
  EXPECT_EQ(report.scanlineBytes, 50u * 4);
  EXPECT_EQ(report.storedPages, VirtualTextureReader(dir_ / "big.vt").storedPageCount());
}

}  // namespace
}  // namespace vt
