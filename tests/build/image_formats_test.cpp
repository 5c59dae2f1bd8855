// vt build reads every format OpenImageIO reads: each image below is written by OpenImageIO with
// its format's options, built into a texture, and the finest level must hold exactly what
// OpenImageIO decodes from the file (for lossy JPEG too, the decoded texels are the reference).
// Sides are not powers of two.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "build/texture_builder.h"
#include "format/level_image.h"
#include "format/virtual_texture_reader.h"
#include "test_support.h"

namespace vt {
namespace {

struct Format {
  std::string name;  // file name, the extension chooses the format
  uint32_t channels;
  OIIO::TypeDesc type;
  std::vector<std::pair<std::string, std::string>> attributes;
};

void writePattern(const std::filesystem::path& path, const Format& format, uint32_t w, uint32_t h) {
  std::vector<float> texels(size_t{w} * h * format.channels);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      for (uint32_t c = 0; c < format.channels; ++c)
        texels[(size_t{y} * w + x) * format.channels + c] =
            static_cast<float>((x * 9 + y * 5 + c * 80 + (x * y) % 17) % 256) / 255.0f;
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(static_cast<int>(w), static_cast<int>(h), static_cast<int>(format.channels),
                       format.type);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  for (const auto& [key, value] : format.attributes) spec.attribute(key, value);
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, texels.data())) << out->geterror();
  ASSERT_TRUE(out->close());
}

std::vector<uint8_t> decode(const std::filesystem::path& path, uint32_t channels) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path.string(), &config);
  EXPECT_TRUE(in);
  const auto& spec = in->spec();
  std::vector<uint8_t> texels(size_t(spec.width) * spec.height * channels);
  EXPECT_TRUE(
      in->read_image(0, 0, 0, static_cast<int>(channels), OIIO::TypeDesc::UINT8, texels.data()));
  return texels;
}

class ImageFormats : public ::testing::TestWithParam<Format> {};

TEST_P(ImageFormats, FinestLevelHoldsTheDecodedImage) {
  test::ScratchDirectory dir;
  const Format& format = GetParam();
  const uint32_t w = 45, h = 37;
  writePattern(dir / format.name, format, w, h);
  // The files really use the variants named: a progressive JPEG has an SOF2 marker, an RLE TGA
  // image type 10 (true colour, run-length encoded).
  const auto bytes = test::readBytes(dir / format.name);
  if (format.name == "progressive.jpg") {
    bool sof2 = false;
    for (size_t i = 0; i + 1 < bytes.size(); ++i)
      sof2 |= bytes[i] == std::byte{0xFF} && bytes[i + 1] == std::byte{0xC2};
    EXPECT_TRUE(sof2);
  }
  if (format.name == "rle.tga") {
    EXPECT_EQ(std::to_integer<int>(bytes[2]), 10);
  }
  const Layout layout = singleImageLayout(
      dir / format.name, {.pageSize = 16, .border = 1, .colorSpace = ColorSpace::kLinear});
  EXPECT_EQ(layout.description.channels, format.channels);
  EXPECT_EQ(layout.description.sideTexels(), 64u);
  buildVirtualTexture(layout, dir / "t.vt", {.progress = false});

  const VirtualTextureReader reader(dir / "t.vt");
  const LevelImage finest = assembleLevel(reader, reader.description().finestLevel());
  const std::vector<uint8_t> expected = decode(dir / format.name, format.channels);
  size_t mismatches = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w * format.channels; ++x)
      mismatches += std::to_integer<uint8_t>(finest.texels[size_t{y} * 64 * format.channels + x]) !=
                    expected[size_t{y} * w * format.channels + x];
  EXPECT_EQ(mismatches, 0u);
  // Pages beyond the image's 45 x 37 texels (of 4 x 4 pages of 16) are not stored.
  EXPECT_EQ(reader.storedPagesPerLevel().back(), 9u);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ImageFormats,
    ::testing::Values(Format{"rgb.png", 3, OIIO::TypeDesc::UINT8, {}},
                      Format{"rgba.png", 4, OIIO::TypeDesc::UINT8, {}},
                      Format{"gray16.png", 1, OIIO::TypeDesc::UINT16, {}},
                      Format{"rle.tga", 4, OIIO::TypeDesc::UINT8, {{"compression", "rle"}}},
                      Format{"plain.tga", 3, OIIO::TypeDesc::UINT8, {{"compression", "none"}}},
                      Format{"baseline.jpg", 3, OIIO::TypeDesc::UINT8, {}},
                      Format{
                          "progressive.jpg", 3, OIIO::TypeDesc::UINT8, {{"jpeg:progressive", "1"}}},
                      Format{"gray.jpg", 1, OIIO::TypeDesc::UINT8, {}},
                      Format{"lzw.tif", 3, OIIO::TypeDesc::UINT8, {{"compression", "lzw"}}},
                      Format{"half.exr", 4, OIIO::TypeDesc::HALF, {}},
                      Format{"float.tif", 2, OIIO::TypeDesc::FLOAT, {}}),
    [](const auto& info) {
      std::string name = info.param.name;
      for (char& c : name)
        if (c == '.') c = '_';
      return name;
    });

}  // namespace
}  // namespace vt
