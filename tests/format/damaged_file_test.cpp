// Random damage to a valid file: every changed byte, wherever it is, must be reported as an
// InputError on open or when its page is read (the header checksum covers the header, the tables
// checksum the tables, the page checksums the pages), and nothing may crash or read out of bounds
// (the sanitizer build runs this too). Seeds are fixed, so the test is deterministic.

#include <gtest/gtest.h>

#include <random>

#include "build/synthetic_texture.h"
#include "common/error.h"
#include "format/virtual_texture_reader.h"
#include "test_support.h"

namespace vt {
namespace {

// Opens `path` and reads every stored page; returns the error, or "" when all is accepted.
std::string openAndReadAll(const std::filesystem::path& path) {
  try {
    const VirtualTextureReader reader(path);
    std::vector<std::byte> page(reader.description().pageBytes());
    for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot)
      reader.readPage(fromAbsoluteIndex(reader.storedPage(slot)), page);
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

class DamagedFile : public ::testing::TestWithParam<bool> {
 protected:
  void SetUp() override {
    SyntheticTexture texture{{.pageSize = 8, .border = 2, .levelCount = 3, .channels = 3},
                             std::nullopt};
    if (GetParam()) texture.discRadius = 0.15;
    writeSyntheticTexture(dir_ / "valid.vt", texture);
    valid_ = test::readBytes(dir_ / "valid.vt");
    ASSERT_EQ(openAndReadAll(dir_ / "valid.vt"), "");
  }
  test::ScratchDirectory dir_;
  std::vector<std::byte> valid_;
};

TEST_P(DamagedFile, EveryFlippedByteIsDetected) {
  std::mt19937 random(1234);
  const auto path = dir_ / "damaged.vt";
  for (int trial = 0; trial < 400; ++trial) {
    auto bytes = valid_;
    const int flips = 1 + static_cast<int>(random() % 4);
    for (int f = 0; f < flips; ++f) {
      // Half the trials hit the header and tables, where parsing happens.
      const size_t limit = trial % 2 ? bytes.size() : std::min<size_t>(bytes.size(), 1024);
      bytes[random() % limit] ^= std::byte(static_cast<uint8_t>(1 + random() % 255));
    }
    test::writeBytes(path, bytes);
    EXPECT_NE(openAndReadAll(path), "") << "trial " << trial << " was accepted";
  }
}

TEST_P(DamagedFile, EveryTruncationIsDetected) {
  const auto path = dir_ / "short.vt";
  for (size_t size = 0; size < valid_.size(); size += 1 + size / 8) {
    test::writeBytes(path, {valid_.begin(), valid_.begin() + static_cast<long>(size)});
    EXPECT_NE(openAndReadAll(path), "") << "cut at " << size << " was accepted";
  }
}

INSTANTIATE_TEST_SUITE_P(DenseAndSparse, DamagedFile, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "Sparse" : "Dense"; });

}  // namespace
}  // namespace vt
