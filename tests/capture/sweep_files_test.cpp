// The probe pack's sweep files (capture/sweep_files.h): results delta-coded and read back equal,
// requests read strictly, every malformed file refused naming itself and the field.

#include "capture/sweep_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "calibrate/recorded_probes.h"
#include "capture/probe_files.h"
#include "common/error.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

const calibrate::FunctionSweep kSweep = {"log2", "log2(x)", 0x3f000000u,
                                         2 * calibrate::kSweepWidth};

TEST(SweepFiles, ResultsAreDeltaCodedAndReadBackEqual) {
  test::ScratchDirectory dir;
  std::vector<uint32_t> bits(kSweep.count);
  for (size_t i = 0; i < bits.size(); ++i) bits[i] = static_cast<uint32_t>(i * 2654435761u);
  bits[5] = 0xffffffffu;  // a difference that wraps around 2^32
  bits[6] = 0;
  capture::writeSweepResult(dir.path(), kSweep, bits);
  // The file holds the first value, then each value minus its predecessor.
  std::ifstream in(dir / "sweep-log2.delta", std::ios::binary);
  uint32_t stored[7];
  in.read(reinterpret_cast<char*>(stored), sizeof stored);
  EXPECT_EQ(stored[0], bits[0]);
  EXPECT_EQ(stored[1], bits[1] - bits[0]);
  EXPECT_EQ(stored[6], 1u);  // 0 - 0xffffffff, mod 2^32
  EXPECT_EQ(capture::readSweepResult(dir.path(), kSweep), bits);
  EXPECT_EQ(capture::readSweepResult(dir.path(), {"sqrt", "sqrt(x)", 0, 4096}), std::nullopt);

  const calibrate::FunctionSweep depth = {"frag_depth", "x", 0x3f000000u, 4096,
                                          calibrate::SweepTarget::kDepth24};
  capture::writeSweepRequests(dir.path(),
                              {kSweep, {"sqrt", "sqrt(x)", 0x3f800000u, 4096}, depth});
  const auto read = capture::readSweepRequests(dir.path());
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[0], kSweep);
  EXPECT_EQ(read[1].name, "sqrt");
  EXPECT_EQ(read[1].target, calibrate::SweepTarget::kFloatBits);
  EXPECT_EQ(read[2], depth);
  // Only the depth sweep names a target: a request for the result's bits reads as before.
  std::stringstream text;
  text << std::ifstream(dir / "sweeps.json").rdbuf();
  const std::string json = text.str();
  EXPECT_NE(json.find("\"target\": \"depth24\""), std::string::npos);
  EXPECT_EQ(json.find("\"target\""), json.rfind("\"target\""));
}

TEST(SweepFiles, AFolderWithoutSweepsAsksForNone) {
  test::ScratchDirectory dir;
  EXPECT_TRUE(capture::readSweepRequests(dir.path()).empty());
}

TEST(SweepFiles, MalformedRequestsAreRefusedNamingTheFileAndTheField) {
  const std::string head = R"j({"format": "vt-sweeps", "version": 1, "sweeps": [)j";
  const std::string log2 = R"j({"name": "log2", "expression": "log2(x)", "first": 1056964608, )j";
  const std::pair<std::string, std::string> cases[] = {
      {R"j({"format": "vt-sweeps", "version": 1, "sweeps": [], "extra": 1})j",
       "field extra is not a field of a sweep here"},
      {R"j({"format": "vt-sweeps", "version": 2, "sweeps": []})j", "not a vt-sweeps description"},
      {head + log2 + R"j("count": 4095}]})j",
       "sweep 0: field count is not a whole number from 4096 to 33554432"},
      {head + log2 + R"j("count": 6000}]})j", "sweep 0: field count is not a multiple of 4096"},
      {head + R"j({"name": "log2", "expression": "x", "first": 4294963200, "count": 8192}]})j",
       "sweep 0: the inputs run past the last float bits"},
      {head + R"j({"name": "../x", "expression": "x", "first": 0, "count": 4096}]})j",
       "sweep 0: field name is not 1 to 32 of a-z, 0-9 and _"},
      {head + log2 + R"j("count": 4096, "colour": 1}]})j",
       "sweep 0: field colour is not a field of a sweep here"},
      {head + log2 + R"j("count": 4096, "target": "stencil"}]})j",
       "sweep 0: field target is not \"depth24\""},
      {head + log2 + R"j("count": 4096}, )j" + log2 + R"j("count": 8192}]})j",
       "sweep 1: a second sweep named log2"},
      {head + R"j({"name": 7}]})j", "sweeps.json: "},
  };
  for (const auto& [text, problem] : cases) {
    SCOPED_TRACE(text);
    test::ScratchDirectory dir;
    std::ofstream(dir / "sweeps.json") << text;
    EXPECT_THAT([&] { capture::readSweepRequests(dir.path()); },
                ThrowsMessage<InputError>(
                    AllOf(StartsWith((dir / "sweeps.json").string() + ": "), HasSubstr(problem))));
  }
}

TEST(SweepFiles, AResultOfTheWrongSizeIsRefusedBeforeItIsRead) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "sweep-log2.delta") << std::string(4 * kSweep.count + 4, 'x');
  EXPECT_THAT([&] { capture::readSweepResult(dir.path(), kSweep); },
              ThrowsMessage<InputError>(
                  AllOf(StartsWith((dir / "sweep-log2.delta").string() + ": "),
                        HasSubstr("asks for 32772 bytes, the limit is 32768 bytes"))));
  std::ofstream(dir / "sweep-log2.delta", std::ios::trunc) << std::string(12, 'x');
  EXPECT_THAT([&] { capture::readSweepResult(dir.path(), kSweep); },
              ThrowsMessage<InputError>(AllOf(StartsWith((dir / "sweep-log2.delta").string()),
                                              HasSubstr("12 bytes, expected 32768"))));
}

// A folder drawn for another version (its log2 sweep asks for other inputs) is refused by the
// replay, naming its sweeps.json.
TEST(SweepFiles, ASweepForOtherInputsIsRefusedByTheReplay) {
  test::ScratchDirectory dir;
  capture::writeProbeFolder(dir.path(), {1, {"r", "v", "w"}});
  calibrate::FunctionSweep other = calibrate::functionSweeps().front();
  other.count /= 2;
  capture::writeSweepRequests(dir.path(), {other});
  calibrate::RecordedProbeDrawer drawer(dir.path());
  EXPECT_THAT([&] { drawer.sweep(calibrate::functionSweeps().front()); },
              ThrowsMessage<InputError>(
                  AllOf(StartsWith((dir / "sweeps.json").string() + ": "),
                        HasSubstr("sweep log2 is not the one this vt calibrate asks for"))));
  EXPECT_EQ(drawer.sweep(calibrate::functionSweeps().back()), std::nullopt);  // not listed
}

// A sweep the folder lists but whose results it lacks is refused, naming sweeps.json and the
// sweep, rather than fitted without.
TEST(SweepFiles, AListedSweepWithoutResultsIsRefused) {
  test::ScratchDirectory dir;
  capture::writeProbeFolder(dir.path(), {1, {"r", "v", "w"}});
  const calibrate::FunctionSweep log2 = calibrate::functionSweeps().front();
  capture::writeSweepRequests(dir.path(), {log2});
  calibrate::RecordedProbeDrawer drawer(dir.path());
  EXPECT_THAT([&] { drawer.sweep(log2); },
              ThrowsMessage<InputError>(
                  AllOf(StartsWith((dir / "sweeps.json").string() + ": "),
                        HasSubstr("lists sweep log2, but its results are not in the folder"))));
  capture::writeSweepResult(dir.path(), log2, std::vector<uint32_t>(log2.count, 7));
  EXPECT_EQ(calibrate::RecordedProbeDrawer(dir.path()).sweep(log2),
            std::vector<uint32_t>(log2.count, 7));
}

}  // namespace
}  // namespace vt
