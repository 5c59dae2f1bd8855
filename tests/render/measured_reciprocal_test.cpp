// A measured reciprocal as a member (render/measured_reciprocal.h): one binade's table extends to
// every normal input by the exponent and the sign, the rest takes IEEE division; its file is
// checked by size and checksum; a model names it and reads it back from beside itself, and every
// way a model or its table can be wrong is refused naming the file.

#include "render/measured_reciprocal.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <random>

#include "common/error.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

// IEEE 1 / x over [1, 2), with every third result one ulp lower where `perturbed`.
std::vector<uint32_t> tableOf(bool perturbed) {
  std::vector<uint32_t> bits(MeasuredReciprocal::kCount);
  for (uint32_t i = 0; i < bits.size(); ++i) {
    bits[i] = std::bit_cast<uint32_t>(1.0f / std::bit_cast<float>(MeasuredReciprocal::kFirst + i));
    if (perturbed && i % 3 == 1) --bits[i];
  }
  return bits;
}

TEST(MeasuredReciprocal, IeeeTableGivesIeeeDivisionAndAPerturbedOneScalesItsOwn) {
  const MeasuredReciprocal ieee(tableOf(false));
  const MeasuredReciprocal perturbed(tableOf(true));
  EXPECT_NE(ieee.checksum(), perturbed.checksum());
  std::mt19937 random(5);
  uint64_t differing = 0;
  for (int k = 0; k < 200000; ++k) {
    const uint32_t exponent = 1 + random() % 252;  // 2^-126 .. 2^125: normal reciprocals
    const uint32_t mantissa = random() >> 9;
    const uint32_t sign = (random() & 1) << 31;
    const float q = std::bit_cast<float>(sign | (exponent << 23) | mantissa);
    ASSERT_EQ(std::bit_cast<uint32_t>(ieee.of(q)), std::bit_cast<uint32_t>(1.0f / q)) << q;
    // The perturbed table's result at q is its result at q's mantissa, scaled exactly.
    const float m = std::bit_cast<float>(MeasuredReciprocal::kFirst | mantissa);
    const float expected = std::ldexp(perturbed.of(m), 127 - static_cast<int>(exponent));
    ASSERT_EQ(perturbed.of(q), sign ? -expected : expected) << q;
    differing += perturbed.of(q) != 1.0f / q;
  }
  EXPECT_GT(differing, 50000u);  // a third of the mantissas, less the exact ones
  // Outside the table's reach IEEE division: zero, denormals, infinities, huge inputs.
  for (const float q : {0.0f, -0.0f, 0x1p-140f, std::numeric_limits<float>::infinity(), 0x1p127f})
    EXPECT_EQ(std::bit_cast<uint32_t>(perturbed.of(q)), std::bit_cast<uint32_t>(1.0f / q)) << q;
  EXPECT_TRUE(std::isnan(perturbed.of(std::numeric_limits<float>::quiet_NaN())));
  std::vector<uint32_t> wrong = tableOf(false);
  wrong[17] = std::bit_cast<uint32_t>(1.5f);
  EXPECT_THROW(MeasuredReciprocal{wrong}, std::invalid_argument);
  EXPECT_THROW(MeasuredReciprocal{std::vector<uint32_t>(5)}, std::invalid_argument);
}

TEST(MeasuredReciprocal, AModelNamesItsTableAndReadsItBackFromBesideItself) {
  test::ScratchDirectory dir;
  PrecisionModel model = llvmpipeModel();
  model.name = "measured";
  model.arithmetic.reciprocal.table = std::make_shared<const MeasuredReciprocal>(tableOf(true));
  const std::string checksum = model.arithmetic.reciprocal.table->checksum();
  const std::filesystem::path file = dir / "model.json";
  writeModelFiles(file, model.arithmetic, modelJson(model));
  const std::filesystem::path table = dir / reciprocalTableName(checksum);
  ASSERT_TRUE(std::filesystem::exists(table));
  EXPECT_EQ(std::filesystem::file_size(table), 4u * MeasuredReciprocal::kCount);
  const PrecisionModel read = readModelFile(file);
  EXPECT_EQ(read, model);
  ASSERT_TRUE(read.arithmetic.reciprocal.table);
  EXPECT_EQ(read.arithmetic.reciprocal.table->bits(), model.arithmetic.reciprocal.table->bits());
  EXPECT_THAT(describe(read.arithmetic), HasSubstr("the measured reciprocal (table " + checksum));
  // A model without the table is another member.
  EXPECT_NE(readModelFile(file).arithmetic, llvmpipeModel().arithmetic);

  // The table changed in one value: its checksum no longer matches.
  {
    std::fstream f(table, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(400);
    f.put('\x01');
  }
  EXPECT_THAT([&] { readModelFile(file); },
              ThrowsMessage<InputError>(AllOf(StartsWith(table.string() + ": "),
                                              HasSubstr("the model names " + checksum))));
  // Cut short.
  std::filesystem::resize_file(table, 100);
  EXPECT_THAT([&] { readModelFile(file); },
              ThrowsMessage<InputError>(AllOf(StartsWith(table.string() + ": "),
                                              HasSubstr("100 bytes, expected 33554432"))));
  // Missing.
  std::filesystem::remove(table);
  EXPECT_THAT([&] { readModelFile(file); },
              ThrowsMessage<InputError>(StartsWith(table.string() + ": ")));

  // The model's fields: a table named otherwise (no path may reach elsewhere), a checksum that is
  // no checksum, a reciprocal where the perspective divides.
  writeModelFiles(file, model.arithmetic, modelJson(model));
  const std::string text = [&] {
    std::stringstream s;
    s << std::ifstream(file).rdbuf();
    return s.str();
  }();
  const auto refused = [&](const std::string& from, const std::string& to,
                           const std::string& problem) {
    SCOPED_TRACE(to);
    std::string changed = text;
    ASSERT_NE(changed.find(from), std::string::npos);
    changed.replace(changed.find(from), from.size(), to);
    std::ofstream(dir / "changed.json", std::ios::trunc) << changed;
    EXPECT_THAT([&] { readModelFile(dir / "changed.json"); },
                ThrowsMessage<InputError>(
                    AllOf(StartsWith((dir / "changed.json").string() + ": "), HasSubstr(problem))));
  };
  refused("\"table\": \"reciprocal-", "\"table\": \"../reciprocal-",
          "field arithmetic.reciprocal.table is not reciprocal-" + checksum);
  refused("\"checksum\": \"" + checksum, "\"checksum\": \"xyz",
          "field arithmetic.reciprocal.checksum is not 16 hexadecimal digits");
  refused("\"perspective\": \"reciprocal_times\"", "\"perspective\": \"divided\"",
          "the perspective (divided) takes no reciprocal");
}

}  // namespace
}  // namespace vt
