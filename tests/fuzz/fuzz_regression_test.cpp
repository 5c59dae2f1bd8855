// Every input the fuzzers ever crashed on, and each bad input written by hand for a limit, fed to
// the same entry point as its fuzz program (fuzz_targets.h): each must end in success or in one
// InputError line, never in another exception, a crash or a sanitizer report (the sanitizer
// suites run this too). The inputs live in tests/fuzz/regressions/<target>/.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "fuzz/fuzz_targets.h"
#include "test_support.h"

namespace vt {
namespace fuzz {

// Names the parameter of FuzzRegression in test names and messages.
void PrintTo(const Target& target, std::ostream* out) { *out << target.name; }

}  // namespace fuzz
namespace {

const std::filesystem::path kRegressions =
    std::filesystem::path(VT_TEST_SOURCE_DIR) / "fuzz" / "regressions";

std::vector<std::filesystem::path> inputsOf(const std::string& target) {
  std::vector<std::filesystem::path> inputs;
  if (!std::filesystem::is_directory(kRegressions / target)) return inputs;
  for (const auto& entry : std::filesystem::directory_iterator(kRegressions / target))
    if (entry.is_regular_file()) inputs.push_back(entry.path());
  std::sort(inputs.begin(), inputs.end());
  return inputs;
}

class FuzzRegression : public ::testing::TestWithParam<fuzz::Target> {};

TEST_P(FuzzRegression, EveryStoredInputEndsInSuccessOrOneInputError) {
  const fuzz::Target& target = GetParam();
  const std::vector<std::filesystem::path> inputs = inputsOf(target.name);
  for (const std::filesystem::path& input : inputs) {
    SCOPED_TRACE(input.string());
    const std::vector<std::byte> bytes = test::readBytes(input);
    const fuzz::Input data(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    try {
      target.run(data);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
    }
  }
  RecordProperty("inputs", static_cast<int>(inputs.size()));
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegression, ::testing::ValuesIn(fuzz::kTargets),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(FuzzRegression, EveryTargetHasItsFolderOfInputs) {
  for (const fuzz::Target& target : fuzz::kTargets)
    EXPECT_FALSE(inputsOf(target.name).empty()) << target.name;
}

}  // namespace
}  // namespace vt
