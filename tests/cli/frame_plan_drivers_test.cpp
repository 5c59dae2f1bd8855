// One FramePlan feeds every driver (src/eval/frame_plan.h): the same configuration flown through
// `vt fly`, `vt eval` and `vt golden generate` draws the same frames. With a reduced jittered
// needbuffer, the LookAhead camera and delayed readback, every frame's statistics (what the
// analysis saw, requested and streamed) and its quality against the reference image are the same
// in all three (as frames.csv writes them), and its colour image the same file in `vt fly` and
// `vt golden`. The profile is not exact, so that the reference images' arithmetic must be the
// flight's in every driver (vt golden used exact).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "eval/box_room_scene.h"
#include "test_support.h"

namespace vt {
namespace {

TEST(FramePlanDrivers, FlyEvalAndGoldenDrawTheSameFrames) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  test::writeBoxRoomScene(dir.path());
  const std::vector<std::string> scene = {(dir / "t.vt").string(),
                                          "--mesh",
                                          (dir / "room.obj").string(),
                                          "--path",
                                          (dir / "path.json").string(),
                                          "--size",
                                          "64x40",
                                          "--profile",
                                          "llvmpipe"};
  // One configuration, as vt fly and vt golden read it and as one entry of vt eval's file.
  const std::string configuration =
      R"({"name": "planned", "budget": 3, "need_scale": 2, "lookahead": "stopfix",
          "readback": "async", "cache_frames": 6})";
  std::ofstream(dir / "config.json") << configuration;
  std::ofstream(dir / "configs.json") << R"({"configurations": [)" << configuration << "]}";
  const auto run = [&](std::vector<std::string> args, const std::vector<std::string>& extra) {
    args.insert(args.end(), scene.begin(), scene.end());
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CommandResult result = test::runCommand(VT_EXECUTABLE, args, dir.path());
    EXPECT_EQ(result.exitCode, 0) << args[0] << ": " << result.err;
  };
  const std::string config = (dir / "config.json").string();
  run({"fly"},
      {"--config", config, "--quality", "--images-every", "1", "-o", (dir / "fly").string()});
  run({"eval"}, {"--configs", (dir / "configs.json").string(), "-o", (dir / "eval").string()});
  run({"golden", "generate"},
      {"--config", config, "--every", "1", "-o", (dir / "golden").string()});

  const test::CsvTable fly = test::readCsv(dir / "fly" / "frames.csv");
  const test::CsvTable eval = test::readCsv(dir / "eval" / "frames.csv");
  std::ifstream manifest(dir / "golden" / "golden.json");
  const nlohmann::json golden = nlohmann::json::parse(manifest);
  ASSERT_GT(fly.rows.size(), 20u);
  ASSERT_EQ(eval.rows.size(), fly.rows.size());
  ASSERT_EQ(golden["frames"].size(), fly.rows.size());
  size_t streamed = 0;
  for (size_t f = 0; f < fly.rows.size(); ++f) {
    for (const char* column :
         {"frame", "covered_pixels", "needed_pages", "hits", "misses", "requested", "streamed",
          "evicted", "resident", "rmse", "ssim", "wssim"}) {
      ASSERT_THAT(fly.columns, ::testing::Contains(column));
      EXPECT_EQ(eval.at(f, column), fly.at(f, column)) << "frame " << f << ", " << column;
    }
    for (const char* measure : {"rmse", "ssim", "wssim"}) {
      std::ostringstream written;  // as frames.csv writes it
      written << golden["frames"][f][measure].get<double>();
      EXPECT_EQ(written.str(), fly.at(f, measure)) << "frame " << f << ", " << measure;
    }
    // The colour itself: the same image file from vt fly and vt golden.
    const std::string image = golden["frames"][f]["image"].get<std::string>();
    EXPECT_EQ(test::readBytes(dir / "fly" / image), test::readBytes(dir / "golden" / image))
        << image;
    streamed += std::stoul(fly.at(f, "streamed"));
  }
  EXPECT_GT(streamed, 0u);  // the cache state changed along the flight
}

}  // namespace
}  // namespace vt
