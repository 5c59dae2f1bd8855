// `vt build` killed with SIGKILL at random moments (crash_consistency.h): its output path holds
// the previous texture or the complete new one, never a partial file `vt info` accepts, and what
// a kill leaves beside it is a hidden temporary file that `vt info` rejects (its header is
// written last) or, killed between the header and the rename, the complete texture. The same for
// the folders `vt eval` and `vt golden generate` write: the previous folder or the complete new
// one, every file of it.

#include "cli/crash_consistency.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "common/image_file.h"
#include "eval/box_room_scene.h"
#include "test_support.h"

namespace vt {
namespace {

// An RGB image of smooth ramps and a fine pattern: quick to write; its build takes a few hundred
// ms (seconds under the sanitizers), half of it start-up.
void writeTestImage(const std::filesystem::path& path, uint32_t side, uint32_t seed) {
  std::vector<std::byte> texels(size_t{side} * side * 3);
  for (uint32_t y = 0; y < side; ++y)
    for (uint32_t x = 0; x < side; ++x) {
      std::byte* texel = &texels[(size_t{y} * side + x) * 3];
      texel[0] = std::byte(static_cast<uint8_t>(x * 255 / side));
      texel[1] = std::byte(static_cast<uint8_t>(y * 255 / side));
      texel[2] = std::byte(static_cast<uint8_t>(((x ^ y) + seed) * 37));
    }
  writeImage8(path, side, side, 3, texels);
}

class CrashConsistency : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(dir_ / "out");
    std::filesystem::create_directories(dir_ / "log");
    writeTestImage(dir_ / "large.png", 1024, 1);
  }

  // `vt build` of the large image to out/texture.vt, a complete output being one `vt info`
  // opens.
  test::CrashTarget buildTarget() {
    test::CrashTarget target;
    target.program = VT_EXECUTABLE;
    target.output = dir_ / "out" / "texture.vt";
    target.args = {
        "build", (dir_ / "large.png").string(), "-o", target.output.string(), "-q", "--threads",
        "2"};
    target.accepts = [this](const std::filesystem::path& file) {
      return test::runCommand(VT_EXECUTABLE, {"info", file.string()}, dir_.path()).exitCode == 0;
    };
    return target;
  }

  static void expectConsistent(const test::CrashReport& report, int kills) {
    EXPECT_THAT(report.problems, ::testing::IsEmpty());
    int killedMidway = 0;
    size_t leftovers = 0;
    for (const test::CrashRun& run : report.runs) {
      killedMidway += !run.finished;
      leftovers += run.leftovers;
      std::cout << "killed after " << run.killedAfter << " s: " << run.outcome << ", "
                << run.leftovers << " temporary file(s) left\n";
    }
    std::cout << "uninterrupted run " << report.fullRunSeconds << " s, writing from "
              << report.writingFromSeconds << " s\n";
    EXPECT_EQ(report.runs.size(), static_cast<size_t>(kills));
    // Kills fall uniformly over the run's duration, so most land before its end; on a loaded
    // machine the run stretches and fewer do. At least one must, or nothing is shown.
    EXPECT_GE(killedMidway, 1);
    ::testing::Test::RecordProperty("leftovers", static_cast<int>(leftovers));
  }

  test::ScratchDirectory dir_;
};

TEST_F(CrashConsistency, KilledBuildLeavesThePreviousTextureOrTheCompleteNewOne) {
  // The previous complete file at the output path: another texture.
  writeTestImage(dir_ / "small.png", 256, 2);
  const test::CommandResult previous = test::runCommand(
      VT_EXECUTABLE,
      {"build", (dir_ / "small.png").string(), "-o", (dir_ / "out" / "texture.vt").string(), "-q"},
      dir_.path());
  ASSERT_EQ(previous.exitCode, 0) << previous.err;
  const test::CrashReport report =
      test::killAtRandomMoments(buildTarget(), 10, 20261121, dir_ / "log");
  expectConsistent(report, 10);
}

TEST_F(CrashConsistency, KilledFirstBuildLeavesNoTextureOrTheCompleteOne) {
  const test::CrashReport report = test::killAtRandomMoments(buildTarget(), 6, 7, dir_ / "log");
  expectConsistent(report, 6);
}

// A texture and the box room's files for the folder outputs.
class FolderCrashConsistency : public CrashConsistency {
 protected:
  void SetUp() override {
    CrashConsistency::SetUp();
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
    test::writeBoxRoomScene(dir_.path());
  }

  // Runs `args` to completion: the previous output at the path.
  void runOnce(const std::vector<std::string>& args) {
    const test::CommandResult result = test::runCommand(VT_EXECUTABLE, args, dir_.path());
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  }

  // vt with `args`, to be killed while it writes the folder `output`.
  static test::CrashTarget folderTarget(std::vector<std::string> args,
                                        const std::filesystem::path& output) {
    test::CrashTarget target;
    target.program = VT_EXECUTABLE;
    target.args = std::move(args);
    target.output = output;
    target.folder = true;
    return target;
  }
};

TEST_F(FolderCrashConsistency, KilledEvalLeavesThePreviousResultsOrTheCompleteNewOnes) {
  const std::filesystem::path output = dir_ / "out" / "eval";
  const auto eval = [&](const std::string& heuristics) {
    return std::vector<std::string>{"eval",        (dir_ / "t.vt").string(),
                                    "--mesh",      (dir_ / "room.obj").string(),
                                    "--path",      (dir_ / "path.json").string(),
                                    "--size",      "64x40",
                                    "--heuristic", heuristics,
                                    "--budget",    "3",
                                    "--jobs",      "1",
                                    "-o",          output.string()};
  };
  ASSERT_NO_FATAL_FAILURE(runOnce(eval("pixelsum")));
  test::CrashTarget target = folderTarget(eval("pixelsum,distance,pixelsum*noisevalue"), output);
  // The summaries hold run times; the other files are compared byte for byte.
  target.variableFiles = {"summary.json", "summary.md"};
  // Complete: every file of the results, the summary naming the runs frames.csv holds.
  target.accepts = [](const std::filesystem::path& folder) {
    for (const char* file : {"frames.csv", "summary.json", "summary.md", "ssim.png", "wssim.png",
                             "rmse.png", "ssim.svg", "wssim.svg", "rmse.svg"})
      if (!std::filesystem::exists(folder / file)) return false;
    std::ifstream summaryFile(folder / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(summaryFile, nullptr, false);
    std::ifstream frames(folder / "frames.csv");
    std::string line, lastLine;
    while (std::getline(frames, line)) lastLine = line;  // "configuration,frame,...": the last run
    return summary.is_object() && summary.contains("runs") && !lastLine.empty() &&
           std::to_string(summary["runs"].size() - 1) == lastLine.substr(0, lastLine.find(','));
  };
  const test::CrashReport report = test::killAtRandomMoments(target, 6, 11, dir_ / "log");
  expectConsistent(report, 6);
}

TEST_F(FolderCrashConsistency, KilledGoldenGenerateLeavesThePreviousSetOrTheCompleteNewOne) {
  const std::filesystem::path output = dir_ / "out" / "golden";
  const auto generate = [&](const std::string& every) {
    return std::vector<std::string>{"golden",
                                    "generate",
                                    (dir_ / "t.vt").string(),
                                    "--mesh",
                                    (dir_ / "room.obj").string(),
                                    "--path",
                                    (dir_ / "path.json").string(),
                                    "--size",
                                    "64x40",
                                    "--every",
                                    every,
                                    "-o",
                                    output.string()};
  };
  ASSERT_NO_FATAL_FAILURE(runOnce(generate("5")));
  test::CrashTarget target = folderTarget(generate("3"), output);
  target.accepts = [](const std::filesystem::path& folder) {
    return std::filesystem::exists(folder / "golden.json");
  };
  const test::CrashReport report = test::killAtRandomMoments(target, 6, 12, dir_ / "log");
  expectConsistent(report, 6);
}

}  // namespace
}  // namespace vt
