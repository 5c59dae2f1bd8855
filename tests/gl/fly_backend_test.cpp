// `vt fly --backend gl` against `--backend oracle`: streaming decides from the needbuffer (and
// the depth, for Distance) each backend reads back, so on llvmpipe, where the oracle matches the
// driver bit for bit, both flights stream the same pages in every frame, also when the needbuffer
// arrives a frame late through the GL path's asynchronous readback.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(FlyBackend, GlAndOracleStreamTheSamePagesWithDistanceReducedNeedbuffersAndAsyncReadback) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, std::nullopt});
  const auto fly = [&](const std::string& backend, const std::string& needScale,
                       const std::string& readback) {
    const std::string out = (dir / (backend + needScale + readback)).string();
    const auto result = test::runCommand(VT_EXECUTABLE,
                                         {"fly",
                                          (dir / "t.vt").string(),
                                          "--backend",
                                          backend,
                                          "--profile",
                                          "llvmpipe",
                                          "--size",
                                          "128x80",
                                          "--budget",
                                          "4",
                                          "--cache-frames",
                                          "6",
                                          "--heuristic",
                                          "distance*pixelsum",
                                          "--lookahead",
                                          "plain",
                                          "--need-scale",
                                          needScale,
                                          "--readback",
                                          readback,
                                          "-o",
                                          out},
                                         dir.path());
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_THAT(result.out, HasSubstr("flew 51 frames"));
    return test::readBytes(std::filesystem::path(out) / "frames.csv");
  };
  for (const auto& [needScale, readback] : std::vector<std::pair<std::string, std::string>>{
           {"1", "sync"}, {"2", "sync"}, {"1", "async"}, {"4", "async"}}) {
    SCOPED_TRACE(needScale + " " + readback);
    const auto gl = fly("gl", needScale, readback), oracle = fly("oracle", needScale, readback);
    const test::CommandResult probe =
        test::runCommand(VT_EXECUTABLE,
                         {"render", (dir / "t.vt").string(), "--backend", "gl", "--size", "8x8",
                          "-o", (dir / "probe.png").string()},
                         dir.path());
    if (probe.out.find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma")) {
      EXPECT_EQ(gl, oracle);
    }
  }
}

}  // namespace
}  // namespace vt
