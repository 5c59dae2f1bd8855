// A probe result that is not a finite number is refused by `vt calibrate --probes` (exit 1, the
// rule, the probe and the value; no model written): a comparison with NaN is false, so such a value
// would slip past every bound and become the model. The H100's committed probes
// (data/gpus/nvidia-h100/probes.tar.gz), each time with one value replaced: every other value is
// the GPU's own, so the calibration would otherwise succeed.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

// Overwrites the float at byte `offset` of `file`.
void writeFloat(const std::filesystem::path& file, size_t offset, float value) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(offset));
  f.write(reinterpret_cast<const char*>(&value), sizeof value);
  ASSERT_TRUE(f.good()) << file;
}

// Byte offset of the first covered pixel's depth in a triangle probe's result (per pixel the
// triangle as int32, then s, t, ds/dx, dt/dx, ds/dy, dt/dy and depth as floats).
size_t firstCoveredDepth(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  int32_t pixel[8];
  for (size_t i = 0; in.read(reinterpret_cast<char*>(pixel), sizeof pixel); ++i)
    if (pixel[0] >= 0) return i * sizeof pixel + 7 * sizeof(float);
  return 0;
}

TEST(CalibrateProbes, ANonFiniteResultIsRefusedNamingTheProbeAndTheValue) {
  const std::filesystem::path evidence =
      std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data" / "gpus" / "nvidia-h100";
  struct Case {
    const char* file;
    bool covered;  // a triangle probe: the first covered pixel's depth
    size_t offset;
    float value;
    const char* expected;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const Case cases[] = {
      // log2 of the first input (channel 0 of sample 0).
      {"probe-0000.result", false, 0, nan,
       "'result = vec4(log2(x.x), sqrt(x.x), x.z * x.y, "
       "0.0);' returned NaN in channel 0 of sample 0"},
      // sqrt of input 100 (channel 1 of sample 100).
      {"probe-0000.result", false, (100 * 4 + 1) * 4, -inf,
       "returned -infinity in channel 1 of "
       "sample 100"},
      // One GL_LINEAR sample of 32,768, all the others right.
      {"probe-0004.result", false, (32767 * 4 + 2) * 4, inf,
       "'result = textureLod(uTexture, x.xy, 0.0);' returned +infinity in channel 2 of sample "
       "32767"},
      // A covered pixel's depth in the random triangles.
      {"probe-0011.result", true, 0, nan, "the triangle probe of "},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    test::ScratchDirectory dir;
    const test::CommandResult unpacked = test::runCommand(
        "/bin/tar", {"-C", dir.path().string(), "-xzf", (evidence / "probes.tar.gz").string()},
        dir.path());
    ASSERT_EQ(unpacked.exitCode, 0) << unpacked.err;
    const std::filesystem::path file = dir / "probes" / c.file;
    const size_t offset = c.covered ? firstCoveredDepth(file) : c.offset;
    if (c.covered) {
      ASSERT_GT(offset, 0u) << "no covered pixel in " << file;
    }
    ASSERT_NO_FATAL_FAILURE(writeFloat(file, offset, c.value));
    const test::CommandResult calibrated = test::runCommand(
        VT_EXECUTABLE,
        {"calibrate", "--probes", (dir / "probes").string(), "-o", (dir / "model.json").string()},
        dir.path());
    EXPECT_EQ(calibrated.exitCode, 1) << calibrated.out << calibrated.err;
    EXPECT_THAT(calibrated.err, HasSubstr("breaks a rule (GL 4.5 core, section 2.3.4"));
    EXPECT_THAT(calibrated.err, HasSubstr(c.expected));
    EXPECT_THAT(calibrated.err, HasSubstr("where the exact result is a finite number"));
    EXPECT_FALSE(std::filesystem::exists(dir / "model.json"));
  }
}

}  // namespace
}  // namespace vt
