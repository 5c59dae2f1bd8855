// common/image_file.h: both PNG compressions store the texels exactly, and they are two different
// encodings (the fast one's settings reach the writer).

#include "common/image_file.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "test_support.h"

namespace vt {
namespace {

// Smooth gradients with noise on top: what the row filters and the compression level act on.
std::vector<uint8_t> texels(uint32_t width, uint32_t height) {
  std::vector<uint8_t> t(size_t{width} * height * 4);
  std::mt19937 random(5);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (uint32_t c = 0; c < 4; ++c)
        t[(size_t{y} * width + x) * 4 + c] =
            static_cast<uint8_t>((x * (c + 1) + y * 3 + random() % 4) & 0xff);
  return t;
}

TEST(ImageFile, BothPngCompressionsStoreTheTexelsExactlyAndDiffer) {
  test::ScratchDirectory dir;
  constexpr uint32_t kWidth = 96, kHeight = 64;
  const std::vector<uint8_t> image = texels(kWidth, kHeight);
  const auto bytes = std::as_bytes(std::span(image));
  writeImage8(dir / "small.png", kWidth, kHeight, 4, bytes, PngCompression::kSmall);
  writeImage8(dir / "fast.png", kWidth, kHeight, 4, bytes, PngCompression::kFast);
  for (const char* name : {"small.png", "fast.png"}) {
    const Image8 read = readImage8(dir / name, 1024);
    EXPECT_EQ(read.width, static_cast<int>(kWidth)) << name;
    EXPECT_EQ(read.height, static_cast<int>(kHeight)) << name;
    EXPECT_EQ(read.channels, 4) << name;
    EXPECT_EQ(read.texels, image) << name;
  }
  EXPECT_NE(std::filesystem::file_size(dir / "small.png"),
            std::filesystem::file_size(dir / "fast.png"));
}

}  // namespace
}  // namespace vt
