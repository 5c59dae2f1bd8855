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
#include <functional>
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

float readFloat(const std::filesystem::path& file, size_t offset) {
  std::ifstream in(file, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(offset));
  float value = 0;
  in.read(reinterpret_cast<char*>(&value), sizeof value);
  return value;
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

// The H100's probes unpacked into a scratch folder, one value changed, then calibrated.
struct Recalibrated {
  test::ScratchDirectory dir;
  test::CommandResult result;
};

void recalibrate(Recalibrated& r, const char* probe, bool covered, size_t offset,
                 const std::function<float(float)>& change) {
  const std::filesystem::path evidence =
      std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data" / "gpus" / "nvidia-h100";
  const test::CommandResult unpacked = test::runCommand(
      "/bin/tar", {"-C", r.dir.path().string(), "-xzf", (evidence / "probes.tar.gz").string()},
      r.dir.path());
  ASSERT_EQ(unpacked.exitCode, 0) << unpacked.err;
  const std::filesystem::path file = r.dir / "probes" / probe;
  if (covered) {
    offset = firstCoveredDepth(file);
    ASSERT_GT(offset, 0u) << "no covered pixel in " << file;
  }
  ASSERT_NO_FATAL_FAILURE(writeFloat(file, offset, change(readFloat(file, offset))));
  r.result = test::runCommand(
      VT_EXECUTABLE,
      {"calibrate", "--probes", (r.dir / "probes").string(), "-o", (r.dir / "model.json").string()},
      r.dir.path());
}

TEST(CalibrateProbes, ANonFiniteResultIsRefusedNamingTheProbeAndTheValue) {
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
    Recalibrated r;
    ASSERT_NO_FATAL_FAILURE(
        recalibrate(r, c.file, c.covered, c.offset, [&](float) { return c.value; }));
    EXPECT_EQ(r.result.exitCode, 1) << r.result.out << r.result.err;
    EXPECT_THAT(r.result.err, HasSubstr("breaks a rule (GL 4.5 core, section 2.3.4"));
    EXPECT_THAT(r.result.err, HasSubstr(c.expected));
    EXPECT_THAT(r.result.err, HasSubstr("where the exact result is a finite number"));
    EXPECT_FALSE(std::filesystem::exists(r.dir / "model.json"));
  }
}

// A GPU right at every input but one is still refused: the one value's error is the bound, and
// the bound beyond the specification's is the rule it breaks. Denormals stand in for a result that
// collapsed to (almost) zero.
TEST(CalibrateProbes, OneWrongValueAmongRightOnesIsRefusedNamingTheRule) {
  struct Case {
    const char* file;
    size_t offset;
    std::function<float(float)> change;
    const char* expected;
  };
  const Case cases[] = {
      // sqrt of input 100 (2.79e-8) off by about 2^11 ulps.
      {"probe-0000.result", (100 * 4 + 1) * 4, [](float v) { return v * (1 + 0x1p-12f); },
       "breaks a rule: sqrt error in ulps"},
      // log2 of input 100 (outside [0.5, 2]) collapsed to a denormal.
      {"probe-0000.result", (100 * 4 + 0) * 4, [](float) { return 1e-40f; },
       "breaks a rule: log2 error in ulps outside [0.5, 2]"},
      // One GL_LINEAR channel (205/255) collapsed to a denormal.
      {"probe-0004.result", (1000 * 4 + 1) * 4, [](float) { return 1e-40f; },
       "breaks a rule: GL_LINEAR error in units of 1/255"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    Recalibrated r;
    ASSERT_NO_FATAL_FAILURE(recalibrate(r, c.file, false, c.offset, c.change));
    EXPECT_EQ(r.result.exitCode, 1) << r.result.out << r.result.err;
    EXPECT_THAT(r.result.err, HasSubstr(c.expected));
    EXPECT_THAT(r.result.err, HasSubstr("is not conformant"));
    EXPECT_FALSE(std::filesystem::exists(r.dir / "model.json"));
  }
}

}  // namespace
}  // namespace vt
