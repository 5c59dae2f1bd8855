// Measured tables as members (render/measured_table.h): the reciprocal's binade and sqrt's two
// binades extend to every normal input by the exponent (and the reciprocal's sign), the rest
// takes IEEE division or sqrt; a table's file is checked by size and checksum; a model names its
// tables and reads them back from beside itself, and every way a model or a table can be wrong is
// refused naming the file.

#include "render/measured_table.h"

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
  std::vector<uint32_t> bits(MeasuredTable::kReciprocalCount);
  for (uint32_t i = 0; i < bits.size(); ++i) {
    bits[i] =
        std::bit_cast<uint32_t>(1.0f / std::bit_cast<float>(MeasuredTable::kReciprocalFirst + i));
    if (perturbed && i % 3 == 1) --bits[i];
  }
  return bits;
}

// IEEE sqrt over [1, 4), with every third result one ulp higher where `perturbed` (none reaches 2:
// the last is the float below it).
std::vector<uint32_t> sqrtTableOf(bool perturbed) {
  std::vector<uint32_t> bits(MeasuredTable::kSqrtCount);
  for (uint32_t i = 0; i < bits.size(); ++i) {
    bits[i] = std::bit_cast<uint32_t>(std::sqrt(std::bit_cast<float>(MeasuredTable::kSqrtFirst + i)));
    if (perturbed && i % 3 == 2 && std::bit_cast<float>(bits[i] + 1) < 2.0f) ++bits[i];
  }
  return bits;
}

TEST(MeasuredTable, IeeeSqrtTableGivesIeeeSqrtAndAPerturbedOneScalesItsOwn) {
  const MeasuredTable ieee(TabledFunction::kSqrt, sqrtTableOf(false));
  const MeasuredTable perturbed(TabledFunction::kSqrt, sqrtTableOf(true));
  std::mt19937 random(6);
  uint64_t differing = 0;
  for (int k = 0; k < 200000; ++k) {
    const uint32_t exponent = 1 + random() % 254;  // every normal float
    const float x =
        std::bit_cast<float>((exponent << 23) | static_cast<uint32_t>(random() >> 9));
    ASSERT_EQ(std::bit_cast<uint32_t>(ieee.of(x)), std::bit_cast<uint32_t>(std::sqrt(x))) << x;
    // The perturbed table at x is its value at x 4^-k, in [1, 4), times 2^k.
    const int e = static_cast<int>(exponent) - 127;
    const int half = e >= 0 ? e / 2 : -((1 - e) / 2);
    const float m = std::ldexp(x, -2 * half);
    ASSERT_TRUE(m >= 1.0f && m < 4.0f) << x;
    ASSERT_EQ(perturbed.of(x), std::ldexp(perturbed.of(m), half)) << x;
    differing += perturbed.of(x) != std::sqrt(x);
  }
  EXPECT_GT(differing, 50000u);
  // Outside the table's reach IEEE sqrt: zero, denormals, infinity, negative numbers.
  for (const float x : {0.0f, -0.0f, 0x1p-140f, std::numeric_limits<float>::infinity()})
    EXPECT_EQ(std::bit_cast<uint32_t>(perturbed.of(x)), std::bit_cast<uint32_t>(std::sqrt(x))) << x;
  EXPECT_TRUE(std::isnan(perturbed.of(-4.0f)));
  std::vector<uint32_t> wrong = sqrtTableOf(false);
  wrong[3] = std::bit_cast<uint32_t>(0.75f);
  EXPECT_THROW((MeasuredTable{TabledFunction::kSqrt, wrong}), std::invalid_argument);
}

TEST(MeasuredTable, IeeeReciprocalTableGivesIeeeDivisionAndAPerturbedOneScalesItsOwn) {
  const MeasuredTable ieee(TabledFunction::kReciprocal, tableOf(false));
  const MeasuredTable perturbed(TabledFunction::kReciprocal, tableOf(true));
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
    const float m = std::bit_cast<float>(MeasuredTable::kReciprocalFirst | mantissa);
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
  EXPECT_THROW((MeasuredTable{TabledFunction::kReciprocal, wrong}), std::invalid_argument);
  EXPECT_THROW((MeasuredTable{TabledFunction::kReciprocal, std::vector<uint32_t>(5)}),
               std::invalid_argument);
}

// log2 over [1, 2) as the float nearest the exact value, one ulp high at every third input where
// `perturbed`.
std::vector<uint32_t> log2TableOf(bool perturbed) {
  std::vector<uint32_t> bits(MeasuredTable::kLog2Count);
  for (uint32_t i = 0; i < bits.size(); ++i) {
    const double m = std::bit_cast<float>(MeasuredTable::kLog2First + i);
    bits[i] = std::bit_cast<uint32_t>(static_cast<float>(std::log2(m)));
    if (perturbed && i % 3 == 1) ++bits[i];
  }
  return bits;
}

TEST(MeasuredTable, ALog2TableAddsTheExponentInOneFloatAddition) {
  const MeasuredTable table(TabledFunction::kLog2, log2TableOf(true));
  std::mt19937 random(7);
  for (int k = 0; k < 200000; ++k) {
    const uint32_t exponent = 1 + random() % 254;
    const uint32_t mantissa = static_cast<uint32_t>(random() >> 9);
    const float x = std::bit_cast<float>((exponent << 23) | mantissa);
    const float m = std::bit_cast<float>(MeasuredTable::kLog2First | mantissa);
    const float e = static_cast<float>(static_cast<int>(exponent) - 127);
    ASSERT_EQ(std::bit_cast<uint32_t>(table.of(x)), std::bit_cast<uint32_t>(e + table.of(m))) << x;
  }
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(table.of(0.0f), -inf);
  EXPECT_EQ(table.of(-0.0f), -inf);
  EXPECT_EQ(table.of(0x1p-140f), -inf);  // a denormal, as flushed
  EXPECT_EQ(table.of(inf), inf);
  EXPECT_TRUE(std::isnan(table.of(-1.0f)));
  EXPECT_TRUE(std::isnan(table.of(-inf)));
  EXPECT_TRUE(std::isnan(table.of(std::numeric_limits<float>::quiet_NaN())));
  std::vector<uint32_t> wrong = log2TableOf(false);
  wrong[9] = std::bit_cast<uint32_t>(-0.25f);
  EXPECT_THROW((MeasuredTable{TabledFunction::kLog2, wrong}), std::invalid_argument);
}

TEST(MeasuredTable, AModelNamesItsTablesAndReadsThemBackFromBesideItself) {
  test::ScratchDirectory dir;
  PrecisionModel model = llvmpipeModel();
  model.name = "measured";
  model.arithmetic.reciprocal.table =
      std::make_shared<const MeasuredTable>(TabledFunction::kReciprocal, tableOf(true));
  model.arithmetic.sqrt.table =
      std::make_shared<const MeasuredTable>(TabledFunction::kSqrt, sqrtTableOf(true));
  model.arithmetic.log2Table.table =
      std::make_shared<const MeasuredTable>(TabledFunction::kLog2, log2TableOf(true));
  const std::string checksum = model.arithmetic.reciprocal.table->checksum();
  const std::string sqrtChecksum = model.arithmetic.sqrt.table->checksum();
  const std::filesystem::path file = dir / "model.json";
  writeModelFiles(file, model.arithmetic, modelJson(model));
  const std::filesystem::path table = dir / tableFileName(TabledFunction::kReciprocal, checksum);
  ASSERT_TRUE(std::filesystem::exists(table));
  EXPECT_EQ(std::filesystem::file_size(table), 4u * MeasuredTable::kReciprocalCount);
  EXPECT_EQ(std::filesystem::file_size(dir / ("sqrt-" + sqrtChecksum + ".table")),
            4u * MeasuredTable::kSqrtCount);
  const PrecisionModel read = readModelFile(file);
  EXPECT_EQ(read, model);
  ASSERT_TRUE(read.arithmetic.reciprocal.table);
  EXPECT_EQ(read.arithmetic.reciprocal.table->bits(), model.arithmetic.reciprocal.table->bits());
  ASSERT_TRUE(read.arithmetic.sqrt.table);
  EXPECT_EQ(read.arithmetic.sqrt.table->bits(), model.arithmetic.sqrt.table->bits());
  ASSERT_TRUE(read.arithmetic.log2Table.table);
  EXPECT_EQ(read.arithmetic.log2Table.table->bits(), model.arithmetic.log2Table.table->bits());
  EXPECT_THAT(describe(read.arithmetic),
              HasSubstr("log2: the measured table " + model.arithmetic.log2Table.table->checksum()));
  EXPECT_THAT(describe(read.arithmetic), HasSubstr("the measured reciprocal (table " + checksum));
  EXPECT_THAT(describe(read.arithmetic), HasSubstr("sqrt: the measured table " + sqrtChecksum));
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
