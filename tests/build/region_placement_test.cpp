// Region placements (layout.h, thesis 3.3.2): a placement repeats part of its image, wrapping in
// both directions. The finest level is checked texel by texel against the definition, computed
// here from the images' texels with the modulo spelled out; the shared whole-image copies are
// checked through ImageRows' memory count.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "build/image_rows.h"
#include "build/layout.h"
#include "build/texture_builder.h"
#include "common/image_file.h"
#include "format/level_image.h"
#include "format/virtual_texture_reader.h"
#include "test_support.h"

namespace vt {
namespace {

struct Image {
  uint32_t width, height, channels;
  std::vector<uint8_t> texels;
};

// Texels that differ from their neighbours in every channel, so a shifted copy cannot pass.
Image pattern(uint32_t width, uint32_t height, uint32_t channels, uint32_t seed) {
  Image image{width, height, channels, std::vector<uint8_t>(size_t{width} * height * channels)};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (uint32_t c = 0; c < channels; ++c)
        image.texels[(size_t{y} * width + x) * channels + c] =
            static_cast<uint8_t>(seed * 101 + x * 13 + y * 59 + c * 97);
  return image;
}

// a mod m with the non-negative remainder, the definition's modulo.
uint64_t mathMod(int64_t a, uint64_t m) {
  const auto n = static_cast<int64_t>(m);
  return static_cast<uint64_t>(((a % n) + n) % n);
}

// Texel (X, Y) of the finest level by the definition: the placement covering it takes image
// texel ((source_x + X - x) mod w, (source_y + Y - y) mod h); the background elsewhere. Images
// have the texture's channel count.
std::vector<uint8_t> expectedFinest(const Layout& layout,
                                    const std::map<std::string, Image>& images) {
  const uint64_t side = layout.description.sideTexels();
  const uint32_t c = layout.description.channels;
  std::vector<uint8_t> texels(side * side * c);
  for (uint64_t t = 0; t < side * side; ++t)
    for (uint32_t k = 0; k < c; ++k) texels[t * c + k] = layout.background[k];
  for (const Placement& p : layout.images) {
    const Image& image = images.at(p.file.filename().string());
    for (uint64_t Y = p.y; Y < p.y + p.height; ++Y)
      for (uint64_t X = p.x; X < p.x + p.width; ++X) {
        const uint64_t u = mathMod(p.sourceX + static_cast<int64_t>(X - p.x), image.width);
        const uint64_t v = mathMod(p.sourceY + static_cast<int64_t>(Y - p.y), image.height);
        for (uint32_t k = 0; k < c; ++k)
          texels[(Y * side + X) * c + k] = image.texels[(v * image.width + u) * c + k];
      }
  }
  return texels;
}

class RegionPlacement : public ::testing::Test {
 protected:
  void addImage(const std::string& name, const Image& image) {
    writeImage8(dir_ / name, image.width, image.height, image.channels,
                std::as_bytes(std::span(image.texels)));
    images_[name] = image;
  }
  std::filesystem::path writeLayout(const nlohmann::json& layout, const std::string& name) {
    std::ofstream(dir_ / name) << layout.dump(2);
    return dir_ / name;
  }
  std::vector<uint8_t> builtFinest(const Layout& layout, const std::string& name) {
    buildVirtualTexture(layout, dir_ / name, {2, false});
    const VirtualTextureReader reader(dir_ / name);
    const LevelImage finest = assembleLevel(reader, reader.description().finestLevel());
    std::vector<uint8_t> texels(finest.texels.size());
    for (size_t i = 0; i < texels.size(); ++i)
      texels[i] = std::to_integer<uint8_t>(finest.texels[i]);
    return texels;
  }

  test::ScratchDirectory dir_;
  std::map<std::string, Image> images_;
};

TEST_F(RegionPlacement, WrapsInBothDirectionsWithNegativeOffsets) {
  addImage("wall.png", pattern(7, 5, 3, 1));
  addImage("floor.png", pattern(9, 6, 3, 2));
  const nlohmann::json json = {
      {"page_size", 16},
      {"border", 1},
      {"side", 64},
      {"color_space", "linear"},
      {"images",
       {// 23 x 13 texels of a 7 x 5 image: more than three repetitions across, two down, starting
        // at image texel (-37 mod 7, -12 mod 5) = (5, 3).
        {{"file", "wall.png"},
         {"x", 3},
         {"y", 2},
         {"width", 23},
         {"height", 13},
         {"source_x", -37},
         {"source_y", -12}},
        // The same image again, smaller than it and starting at
        // (2^40 - 1 mod 7, 2^40 - 1 mod 5) = (1, 0).
        {{"file", "wall.png"},
         {"x", 30},
         {"y", 9},
         {"width", 6},
         {"height", 4},
         {"source_x", 1099511627775},
         {"source_y", 1099511627775}},
        {{"file", "floor.png"}, {"x", 40}, {"y", 40}},
        {{"file", "floor.png"}, {"x", 50}, {"y", 40}, {"height", 20}, {"source_y", -1}}}}};
  const Layout layout = readLayout(writeLayout(json, "layout.json"));
  const std::vector<uint8_t> expected = expectedFinest(layout, images_);
  const std::vector<uint8_t> finest = builtFinest(layout, "region.vt");
  ASSERT_EQ(finest.size(), expected.size());
  for (uint64_t t = 0; t < 64 * 64; ++t)
    for (uint32_t k = 0; k < 3; ++k)
      ASSERT_EQ(int{finest[t * 3 + k]}, int{expected[t * 3 + k]})
          << "texel (" << t % 64 << ", " << t / 64 << ") channel " << k;
  // Spot checks of the definition itself: the first placement's top-left texel is wall (5, 3),
  // its texel 2 to the right wraps to wall (0, 3).
  const Image& wall = images_["wall.png"];
  EXPECT_EQ(finest[(2 * 64 + 3) * 3], wall.texels[(3 * 7 + 5) * 3]);
  EXPECT_EQ(finest[(2 * 64 + 5) * 3], wall.texels[(3 * 7 + 0) * 3]);
}

TEST_F(RegionPlacement, WholeImageRegionGivesTheSameBytesAsAPlainPlacement) {
  // Gray, RGBA and JPEG (read forwards only, 37 rows: bands of 16 and a partial one) images in an
  // RGBA texture: both paths decode and convert channels alike.
  addImage("a.png", pattern(40, 30, 4, 3));
  addImage("b.png", pattern(21, 11, 1, 4));
  addImage("c.jpg", pattern(19, 37, 3, 5));
  const nlohmann::json plain = {{"page_size", 16},
                                {"border", 2},
                                {"filter", "tent"},
                                {"images",
                                 {{{"file", "a.png"}, {"x", 0}, {"y", 0}},
                                  {{"file", "b.png"}, {"x", 40}, {"y", 8}},
                                  {{"file", "c.jpg"}, {"x", 61}, {"y", 0}}}}};
  nlohmann::json region = plain;
  region["images"][0].update({{"width", 40}, {"height", 30}, {"source_x", 0}, {"source_y", 0}});
  // Whole multiples of the image's size.
  region["images"][1].update({{"source_x", -21}, {"source_y", 22}});
  region["images"][2].update({{"source_y", -37 * 3}});
  const Layout plainLayout = readLayout(writeLayout(plain, "plain.json"));
  const Layout regionLayout = readLayout(writeLayout(region, "region.json"));
  for (const Placement& p : regionLayout.images) ASSERT_TRUE(p.region);
  const BuildReport plainReport = buildVirtualTexture(plainLayout, dir_ / "plain.vt", {2, false});
  const BuildReport regionReport =
      buildVirtualTexture(regionLayout, dir_ / "region.vt", {2, false});
  EXPECT_EQ(test::readBytes(dir_ / "plain.vt"), test::readBytes(dir_ / "region.vt"));
  // Most held at once (rows 8..18 cross all three placements): the plain placements hold one
  // scanline each in the image's channels, the regions their whole images in the texture's 4.
  EXPECT_EQ(plainReport.scanlineBytes, 40u * 4 + 21u * 1 + 19u * 3);
  EXPECT_EQ(regionReport.scanlineBytes, (40u * 30 + 21u * 11 + 19u * 37) * 4);
}

// Runs ImageRows over every row of the layout, checking each row against the definition, and
// returns the bytes it held after each row.
std::vector<uint64_t> runRows(const Layout& layout, const std::map<std::string, Image>& images) {
  const std::vector<uint8_t> expected = expectedFinest(layout, images);
  const uint64_t side = layout.description.sideTexels();
  const uint32_t c = layout.description.channels;
  RowRing rows(side, c, 1, layout.background);
  ImageRows source(layout);
  std::vector<uint64_t> held;
  for (uint64_t y = 0; y < side; ++y) {
    source.row(y, rows);
    held.push_back(source.bufferBytes());
    std::vector<uint8_t> row(side * c);
    rows.read(y, 0, side, row.data());
    const bool same = std::equal(row.begin(), row.end(), expected.begin() + y * side * c);
    EXPECT_TRUE(same) << "row " << y;
    if (!same) break;
  }
  return held;
}

TEST_F(RegionPlacement, PlacementsOfOneImageShareOneCopyReleasedAfterTheLast) {
  addImage("wall.png", pattern(10, 8, 3, 5));
  const Image gray1 = pattern(6, 4, 1, 6);
  addImage("gray.png", gray1);
  // wall: rows 0..11 and, side by side, 4..19; again 40..44. gray (spread to RGB): rows 10..29.
  const nlohmann::json json = {
      {"page_size", 16},
      {"side", 64},
      {"images",
       {{{"file", "wall.png"}, {"x", 0}, {"y", 0}, {"height", 12}, {"source_x", 3}},
        {{"file", "wall.png"}, {"x", 10}, {"y", 4}, {"width", 25}, {"height", 16}},
        {{"file", "./wall.png"}, {"x", 0}, {"y", 40}, {"width", 64}, {"height", 5}},
        {{"file", "gray.png"}, {"x", 40}, {"y", 10}, {"width", 13}, {"height", 20}}}}};
  const Layout layout = readLayout(writeLayout(json, "layout.json"));
  Image& spread = images_["gray.png"];  // gray spreads to RGB
  spread.channels = 3;
  spread.texels.clear();
  for (const uint8_t v : gray1.texels) spread.texels.insert(spread.texels.end(), 3, v);
  const std::vector<uint64_t> held = runRows(layout, images_);
  ASSERT_EQ(held.size(), 64u);
  const uint64_t wall = 10 * 8 * 3, gray = 6 * 4 * 3;
  for (uint64_t y = 0; y < 64; ++y) {
    // wall.png is held from its first placement's top (row 0) to its last one's bottom (row 44),
    // one copy however many of its placements cross the row; gray.png on rows 10..29.
    const uint64_t expected = (y < 45 ? wall : 0) + (y >= 10 && y < 30 ? gray : 0);
    EXPECT_EQ(held[y], expected) << "row " << y;
  }
}

TEST_F(RegionPlacement, ThousandsOfPlacementsOfAFewImages) {
  // 4096 faces of 16 x 8 texels on a 1024^2 texture, each showing its own part of one of three
  // images: the images are held once each, the rows match the definition.
  for (uint32_t i = 0; i < 3; ++i)
    addImage(std::string("t") + std::to_string(i) + ".png", pattern(37 + i, 23, 3, i));
  nlohmann::json json = {{"page_size", 64}, {"side", 1024}, {"images", nlohmann::json::array()}};
  for (int j = 0; j < 128; ++j)
    for (int i = 0; i < 32; ++i)
      json["images"].push_back({{"file", std::string("t") + std::to_string((i + j) % 3) + ".png"},
                                {"x", i * 32 + j % 16},
                                {"y", j * 8},
                                {"width", 16},
                                {"height", 8},
                                {"source_x", i * 7 - j * 11},
                                {"source_y", j * 5 - i * 3}});
  const Layout layout = readLayout(writeLayout(json, "layout.json"));
  const std::vector<uint64_t> held = runRows(layout, images_);
  const uint64_t all = (37 + 38 + 39) * 23 * 3;
  // Every image has a placement on row 0 and on the last rows: all three are held throughout.
  EXPECT_EQ(std::count(held.begin(), held.end(), all), 1024);
}

}  // namespace
}  // namespace vt
