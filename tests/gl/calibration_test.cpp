// `vt calibrate` on the implementations this machine has. On llvmpipe the probes must rediscover
// DESIGN section 7 on their own: the calibrated model equals the hand-written `llvmpipe` model in
// every parameter, and the crosscheck under it is bit-exact. On softpipe the calibrated model must
// explain every pixel. A calibration is deterministic.

#include "calibrate/calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "common/posix_file.h"
#include "gl/headless_context.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

bool onLlvmpipeWithFma(const HeadlessContext& context) {
  return context.renderer().find("llvmpipe") != std::string::npos &&
         __builtin_cpu_supports("fma");
}

TEST(Calibration, LlvmpipeRediscoversTheHandWrittenModelParameterByParameter) {
  const HeadlessContext context;
  if (!onLlvmpipeWithFma(context)) GTEST_SKIP() << "not llvmpipe with FMA: " << context.renderer();
  const PrecisionModel got = calibrate::calibrate().model;
  const PrecisionModel want = llvmpipeModel();
  EXPECT_EQ(got.arithmetic, want.arithmetic);
  EXPECT_EQ(got.subpixelBits, want.subpixelBits);
  EXPECT_EQ(got.fillRulePinned, want.fillRulePinned);
  EXPECT_EQ(got.depthUlps, want.depthUlps);
  EXPECT_EQ(got.depthRoundsToNearest, want.depthRoundsToNearest);
  EXPECT_EQ(got.attributeUlps, want.attributeUlps);
  EXPECT_EQ(got.log2, want.log2);
  EXPECT_EQ(got.log2AbsoluteError, want.log2AbsoluteError);
  EXPECT_EQ(got.log2Ulps, want.log2Ulps);
  EXPECT_EQ(got.sqrtUlps, want.sqrtUlps);
  EXPECT_EQ(got.arithmeticUlps, want.arithmeticUlps);
  EXPECT_EQ(got.filter, want.filter);
  EXPECT_EQ(got.subTexelBits, want.subTexelBits);
  EXPECT_EQ(got.filterErrorUnits, want.filterErrorUnits);
  EXPECT_EQ(got.colorRoundsToNearest, want.colorRoundsToNearest);
  EXPECT_EQ(got.denormalsPinned, want.denormalsPinned);
  // And nothing else: the fields above are all the parameters.
  PrecisionModel same = got;
  same.name = want.name;
  same.renderer = want.renderer;
  same.glVersion = want.glVersion;
  same.sources = want.sources;
  EXPECT_EQ(same, want);
  EXPECT_TRUE(got.pinned());
  EXPECT_EQ(got.renderer, context.renderer());
  EXPECT_EQ(got.glVersion, context.version());
}

TEST(Calibration, IsDeterministicAndItsFileReadsBackAsTheModel) {
  const HeadlessContext context;
  const calibrate::Calibration first = calibrate::calibrate();
  const std::string json = calibrate::calibrationJson(first);
  EXPECT_EQ(calibrate::calibrationJson(calibrate::calibrate()), json);
  test::ScratchDirectory dir;
  std::ofstream(dir / "model.json") << json;
  EXPECT_EQ(readModelFile(dir / "model.json"), first.model);
  EXPECT_EQ(first.fits.size(), 9u);
  for (const calibrate::ParameterFit& fit : first.fits) EXPECT_GT(fit.probes, 0u) << fit.parameter;
}

TEST(Calibration, AModelFromAnotherDriverVersionIsNamedInAWarning) {
  PrecisionModel model = llvmpipeModel();
  EXPECT_EQ(calibrationMismatch(model, "anything", "4.5"), "");  // shipped
  model.name = "calibrated";
  model.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  model.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
  EXPECT_EQ(calibrationMismatch(model, model.renderer, model.glVersion), "");
  EXPECT_THAT(calibrationMismatch(model, model.renderer, "4.5 (Core Profile) Mesa 23.0.4"),
              HasSubstr("measured with 4.5 (Core Profile) Mesa 22.3.6, this driver is 4.5 (Core "
                        "Profile) Mesa 23.0.4: re-run vt calibrate"));
  EXPECT_THAT(calibrationMismatch(model, "softpipe", model.glVersion),
              HasSubstr("this is softpipe: run vt calibrate here"));
}

// `vt calibrate -o` then `vt crosscheck --model` with the file, on the implementation at hand.
nlohmann::json calibrateAndCrosscheck(const test::ScratchDirectory& dir, std::string* err) {
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  const auto calibration =
      test::runCommand(VT_EXECUTABLE, {"calibrate", "-o", (dir / "model.json").string()},
                       dir.path());
  EXPECT_EQ(calibration.exitCode, 0) << calibration.out << calibration.err;
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--model",
       (dir / "model.json").string(), "-o", (dir / "out").string()},
      dir.path());
  std::cout << calibration.out << result.out;
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  *err = result.err;
  std::ifstream in(dir / "out" / "summary.json");
  return nlohmann::json::parse(in);
}

TEST(CalibrateCommand, TheCalibratedModelGivesTheCrosscheckItsVerdict) {
  test::ScratchDirectory dir;
  std::string err;
  const nlohmann::json summary = calibrateAndCrosscheck(dir, &err);
  EXPECT_EQ(summary["model"], "calibrated");
  EXPECT_EQ(summary["totals"]["unexplained"], 0u);
  EXPECT_EQ(err, "");  // measured here: no warning
  // `auto` (the default) picks the measured model of this renderer from $VT_PRECISION_MODELS.
  std::filesystem::create_directory(dir / "models");
  std::filesystem::copy_file(dir / "model.json", dir / "models" / "here.json");
  ::setenv("VT_PRECISION_MODELS", (dir / "models").c_str(), 1);
  const auto automatic = test::runCommand(
      VT_EXECUTABLE,
      {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--scenes", "room", "-o",
       (dir / "auto").string()},
      dir.path());
  ::unsetenv("VT_PRECISION_MODELS");
  EXPECT_EQ(automatic.exitCode, 0) << automatic.out << automatic.err;
  std::ifstream in(dir / "auto" / "summary.json");
  EXPECT_EQ(nlohmann::json::parse(in)["model"], "calibrated");
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos &&
      __builtin_cpu_supports("fma")) {
    EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
    EXPECT_EQ(summary["totals"]["ambiguous_fraction"].get<double>(), 0.0);
  }
}

// softpipe (Mesa's other software rasterizer): its calibrated model must explain every pixel.
// What it pins today: sqrt, the unorm8 conversion, float GL_LINEAR, nearest colour conversion;
// what it leaves (coverage, attributes, depth, log2) is measured or kept at gl45.
TEST(CalibrateCommand, SoftpipesCalibratedModelExplainsEveryPixel) {
  ::setenv("GALLIUM_DRIVER", "softpipe", 1);
  ::setenv("MESA_GL_VERSION_OVERRIDE", "4.5", 1);
  ::setenv("MESA_GLSL_VERSION_OVERRIDE", "450", 1);
  test::ScratchDirectory dir;
  std::string err;
  const nlohmann::json summary = calibrateAndCrosscheck(dir, &err);
  EXPECT_EQ(summary["gl_renderer"], "softpipe");
  EXPECT_EQ(summary["totals"]["unexplained"], 0u);
  const PrecisionModel model = readModelFile(dir / "model.json");
  EXPECT_EQ(model.renderer, "softpipe");
  EXPECT_EQ(model.sqrtUlps, 0.0);
  EXPECT_EQ(model.arithmeticUlps, 0.0);
  EXPECT_EQ(model.filter, FilterArithmetic::kFloat);
  EXPECT_TRUE(model.colorRoundsToNearest);
  EXPECT_EQ(model.log2, Log2Arithmetic::kBounded);
  EXPECT_LE(model.log2Ulps, gl45Model().log2Ulps);  // within GLSL 4.50's 3 ULP
}

}  // namespace
}  // namespace vt
