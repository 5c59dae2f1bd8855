// The golden images of q3dm6ish (data/golden/q3dm6ish): the map retextured and built as CI does,
// flown along the storyboard the set was made on (data/golden/q3dm6ish.storyboard.json, kept with
// the set: data/paths' storyboard moves faster for the chapter-4 study) with HotSpot x NoiseValue and the LookAhead camera at 5 pages per
// frame, every 40th frame at 160 x 100 under the llvmpipe profile. The oracle must reproduce
// every golden frame bit for bit. Regenerate (after a reviewed change of the rendering) with
//   vt golden generate q3.vt --mesh q3/q3dm6ish.obj --path data/golden/q3dm6ish.storyboard.json
//     --config data/golden/q3dm6ish.config.json --every 40 --profile llvmpipe
//     -o data/golden/q3dm6ish
// on the outputs of test::retextureAndBuildQ3dm6ish (one command line).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/run_command.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kData = std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data";

TEST(Q3dm6ishGolden, TheOracleReproducesEveryGoldenFrame) {
  VT_REQUIRE_OPENARENA(packages);
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(test::retextureAndBuildQ3dm6ish(*packages, dir.path()));
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"golden", "check", (kData / "golden" / "q3dm6ish").string(), "--texture",
       (dir / "q3.vt").string(), "--mesh", (dir / "q3" / "q3dm6ish.obj").string(), "--path",
       (kData / "golden" / "q3dm6ish.storyboard.json").string(), "-o", (dir / "check").string()},
      dir.path());
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("golden check (oracle, model llvmpipe): 10 of 10 frames pass"));
}

}  // namespace
}  // namespace vt
