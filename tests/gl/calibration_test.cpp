// `vt calibrate` on the implementations this machine has. On llvmpipe the probes must rediscover
// docs/design.md section 7 on their own: the calibrated model equals the hand-written `llvmpipe`
// model in every parameter, and the crosscheck under it is bit-exact. On softpipe they must
// rediscover what reference/softpipe-arithmetic.md read from Mesa's source: the calibrated model
// equals the hand-written `softpipe` model, and the crosscheck under it is bit-exact too. A
// calibration is deterministic.

#include "calibrate/calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "calibrate/raster_fit.h"
#include "cli/run_command.h"
#include "common/posix_file.h"
#include "gl/headless_context.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

bool onLlvmpipeWithFma(const HeadlessContext& context) {
  return context.renderer().find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma");
}

// Mesa's other software rasterizer for this process (each test runs in a process of its own):
// softpipe, at the GL version the renderer asks for. Before any context is made.
void useSoftpipe() {
  ::setenv("GALLIUM_DRIVER", "softpipe", 1);
  ::setenv("MESA_GL_VERSION_OVERRIDE", "4.5", 1);
  ::setenv("MESA_GLSL_VERSION_OVERRIDE", "450", 1);
}

const calibrate::ParameterFit& fitOf(const calibrate::Calibration& c, const std::string& name) {
  return calibrate::fitNamed(c.fits, name);
}

// The calibrated arithmetic against a hand-written point, family by family: every family the
// probes pinned to one member has the point's member; where several members reproduced every
// probe (the probes cannot tell them apart), the point's member is one of them. Returns the
// calibrated arithmetic with those families taken from the point.
Arithmetic expectSameChoices(const calibrate::Calibration& c, const Arithmetic& want) {
  Arithmetic got = c.model.arithmetic;
  for (const char* family : {"coverage", "viewport", "plane_setup", "plane_positions",
                             "plane_evaluation", "perspective", "depth_offset", "z24"}) {
    const calibrate::ParameterFit& fit = fitOf(c, family);
    const std::string wanted = calibrate::rasterMemberOf(family, want);
    EXPECT_TRUE(fit.pinned) << family << ": " << fit.finding;
    EXPECT_THAT(fit.consistent, ::testing::Contains(wanted)) << family << ": " << fit.finding;
    if (fit.consistent.size() == 1) {
      EXPECT_EQ(fit.chosen, wanted) << family;
    }
  }
  if (fitOf(c, "depth_offset").consistent.size() > 1)
    got.depth.offsetAndClamp = want.depth.offsetAndClamp;  // unseen by every probe, as above
  EXPECT_EQ(fitOf(c, "log2").chosen, nameOf(kLog2FormNames, want.log2));
  EXPECT_EQ(fitOf(c, "texel_conversion").chosen,
            nameOf(kUnormConversionNames, want.texelConversion));
  // Block decoding: one member for colour and one for alpha, each the only one consistent.
  for (const auto& [family, member] :
       {std::pair{"block_decoding", want.blockDecoding.colour},
        std::pair{"block_decoding_alpha", want.blockDecoding.alpha}}) {
    const calibrate::ParameterFit& fit = fitOf(c, family);
    EXPECT_TRUE(fit.pinned) << family << ": " << fit.finding;
    EXPECT_EQ(fit.consistent,
              std::vector<std::string>{std::string(nameOf(kPaletteRuleNames, member))})
        << family << ": " << fit.finding;
  }
  EXPECT_EQ(describe(got), describe(want));
  return got;
}

// The calibrated model against a hand-written one, parameter by parameter, then as a whole.
void expectSameParameters(const calibrate::Calibration& c, const PrecisionModel& want,
                          const HeadlessContext& context) {
  PrecisionModel got = c.model;
  got.arithmetic = expectSameChoices(c, want.arithmetic);
  EXPECT_EQ(got.subpixelBits, want.subpixelBits);
  EXPECT_EQ(got.fillRulePinned, want.fillRulePinned);
  EXPECT_EQ(got.depthUlps, want.depthUlps);
  EXPECT_EQ(got.depthRoundsToNearest, want.depthRoundsToNearest);
  EXPECT_EQ(got.attributeUlps, want.attributeUlps);
  EXPECT_EQ(got.log2Pinned, want.log2Pinned);
  EXPECT_EQ(got.log2AbsoluteError, want.log2AbsoluteError);
  EXPECT_EQ(got.log2Ulps, want.log2Ulps);
  EXPECT_EQ(got.sqrtUlps, want.sqrtUlps);
  EXPECT_EQ(got.arithmeticUlps, want.arithmeticUlps);
  EXPECT_EQ(got.filterPinned, want.filterPinned);
  EXPECT_EQ(got.subTexelBits, want.subTexelBits);
  EXPECT_EQ(got.filterErrorUnits, want.filterErrorUnits);
  EXPECT_EQ(got.colorPinned, want.colorPinned);
  EXPECT_EQ(got.denormalsPinned, want.denormalsPinned);
  EXPECT_EQ(got.decodingPinned, want.decodingPinned);
  // And nothing else: the fields above are all the parameters.
  PrecisionModel same = got;
  same.name = want.name;
  same.renderer = want.renderer;
  same.glVersion = want.glVersion;
  same.sources = want.sources;
  EXPECT_EQ(same, want);
  EXPECT_EQ(got.pinned(), want.pinned());
  EXPECT_EQ(got.onlyDenormalsFree(), want.onlyDenormalsFree());
  EXPECT_EQ(got.renderer, context.renderer());
  EXPECT_EQ(got.glVersion, context.version());
}

TEST(Calibration, LlvmpipeRediscoversTheHandWrittenModelParameterByParameter) {
  const HeadlessContext context;
  if (!onLlvmpipeWithFma(context)) GTEST_SKIP() << "not llvmpipe with FMA: " << context.renderer();
  const calibrate::Calibration calibration = calibrate::calibrate();
  EXPECT_TRUE(calibration.conformant());
  expectSameParameters(calibration, llvmpipeModel(), context);
  EXPECT_TRUE(llvmpipeModel().pinned());
  // Coverage alone (calibrate/coverage_fit.h) finds rule 2's grid and rule 4's ties too.
  const auto grid = std::find_if(calibration.fits.begin(), calibration.fits.end(),
                                 [](const auto& fit) { return fit.parameter == "subpixel_bits"; });
  ASSERT_NE(grid, calibration.fits.end());
  EXPECT_TRUE(grid->pinned);
  EXPECT_THAT(grid->finding, HasSubstr("exactly one rasterizer of the grid family"));
  EXPECT_THAT(grid->finding,
              HasSubstr("8 sub-pixel bits, round half to even, centres on left and bottom edges "
                        "inside"));
}

// softpipe's model was written from its source (reference/softpipe-arithmetic.md); the probes
// must find the same on their own.
TEST(Calibration, SoftpipeRediscoversTheHandWrittenModelParameterByParameter) {
  useSoftpipe();
  const HeadlessContext context;
  ASSERT_EQ(context.renderer(), "softpipe");
  const calibrate::Calibration calibration = calibrate::calibrate();
  EXPECT_TRUE(calibration.conformant());
  expectSameParameters(calibration, softpipeModel(), context);
  EXPECT_TRUE(softpipeModel().onlyDenormalsFree());
}

TEST(Calibration, IsDeterministicAndItsFileReadsBackAsTheModel) {
  const HeadlessContext context;
  const calibrate::Calibration first = calibrate::calibrate();
  const std::string json = calibrate::calibrationJson(first);
  EXPECT_EQ(calibrate::calibrationJson(calibrate::calibrate()), json);
  test::ScratchDirectory dir;
  std::ofstream(dir / "model.json") << json;
  EXPECT_EQ(readModelFile(dir / "model.json"), first.model);
  // The families of the evidence, plane_positions, the reciprocal and the noperspective planes
  // included.
  EXPECT_EQ(first.fits.size(), 23u);
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

// `vt calibrate -o` then `vt crosscheck --model` with the file, on the implementation at hand,
// every pixel's set built (the ambiguous fraction of whole frames).
nlohmann::json calibrateAndCrosscheck(const test::ScratchDirectory& dir, std::string* err) {
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  const auto calibration = test::runCommand(
      VT_EXECUTABLE, {"calibrate", "-o", (dir / "model.json").string()}, dir.path());
  EXPECT_EQ(calibration.exitCode, 0) << calibration.out << calibration.err;
  const auto result =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--model",
                        (dir / "model.json").string(), "--all-sets", "-o", (dir / "out").string()},
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
  const auto automatic =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--scenes",
                        "room", "-o", (dir / "auto").string()},
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

// softpipe (Mesa's other software rasterizer): under its calibrated model every pixel is
// identical, and only pixels whose value depends on the denormal mode are ambiguous, against
// more than half of them under gl45 on the same frames (the bound: at most a tenth).
TEST(CalibrateCommand, SoftpipesCalibratedModelIsBitExactWhereGl45IsAmbiguous) {
  useSoftpipe();
  test::ScratchDirectory dir;
  std::string err;
  const nlohmann::json summary = calibrateAndCrosscheck(dir, &err);
  EXPECT_EQ(summary["gl_renderer"], "softpipe");
  EXPECT_EQ(summary["totals"]["unexplained"], 0u);
  EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  const double calibrated = summary["totals"]["ambiguous_fraction"].get<double>();
  const PrecisionModel model = readModelFile(dir / "model.json");
  EXPECT_EQ(model.renderer, "softpipe");
  Arithmetic softpipe = arithmeticPoint("softpipe");
  softpipe.depth.offsetAndClamp = model.arithmetic.depth.offsetAndClamp;  // no probe sees it
  EXPECT_EQ(describe(model.arithmetic), describe(softpipe));
  EXPECT_TRUE(model.onlyDenormalsFree());

  const auto gl45 =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--model",
                        "gl45", "--all-sets", "-o", (dir / "gl45").string()},
                       dir.path());
  EXPECT_EQ(gl45.exitCode, 0) << gl45.out << gl45.err;
  std::ifstream in(dir / "gl45" / "summary.json");
  const double loose = nlohmann::json::parse(in)["totals"]["ambiguous_fraction"].get<double>();
  std::cout << "softpipe ambiguous fraction: calibrated " << calibrated << ", gl45 " << loose
            << "\n";
  EXPECT_GT(loose, 0.1);
  EXPECT_LE(calibrated, loose / 10);
}

// A block-compressed texture's GL cache holds its blocks and the implementation decodes them
// itself: under the shipped model of the implementation at hand (its measured decoding) the
// crosscheck is bit for bit; with the exact point's decoding instead, pinned, pixels differ
// beyond the model; under gl45 (decoding free within every known decoder) nothing is
// unexplained. `setUp` picks the implementation before any context exists.
void expectCompressedCachesDecodeAsTheImplementation(const std::string& modelName) {
  for (const PixelFormat format : {PixelFormat::kBc1, PixelFormat::kBc3}) {
    SCOPED_TRACE(toString(format));
    test::ScratchDirectory dir;
    TextureDescription d{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4};
    d.format = format;
    writeSyntheticTexture(dir / "t.vt", {d, 0.45});
    PrecisionModel wrong = namedModel(modelName);
    wrong.name = "wrong_decoding";
    wrong.arithmetic.blockDecoding = arithmeticPoint("exact").blockDecoding;
    ASSERT_NE(wrong.arithmetic.blockDecoding, namedModel(modelName).arithmetic.blockDecoding);
    std::ofstream(dir / "wrong.json") << modelJson(wrong);
    const auto totals = [&](const std::string& model, const std::string& out) {
      const auto run = test::runCommand(VT_EXECUTABLE,
                                        {"crosscheck", (dir / "t.vt").string(), "--size", "160x100",
                                         "--model", model, "-o", (dir / out).string()},
                                        dir.path());
      std::cout << run.out;
      std::ifstream in(dir / out / "summary.json");
      return nlohmann::json::parse(in)["totals"];
    };
    const nlohmann::json own = totals(modelName, "own");
    EXPECT_EQ(own["identical"], own["pixels"]);
    EXPECT_GT(totals((dir / "wrong.json").string(), "wrong")["unexplained"].get<uint64_t>(), 0u);
    EXPECT_EQ(totals("gl45", "gl45")["unexplained"], 0u);
  }
}

TEST(CalibrateCommand, LlvmpipeDecodesCompressedCachesAsItsModelSays) {
  const HeadlessContext context;
  if (!onLlvmpipeWithFma(context)) GTEST_SKIP() << "not llvmpipe with FMA: " << context.renderer();
  expectCompressedCachesDecodeAsTheImplementation("llvmpipe");
}

TEST(CalibrateCommand, SoftpipeDecodesCompressedCachesAsItsModelSays) {
  useSoftpipe();
  expectCompressedCachesDecodeAsTheImplementation("softpipe");
}

}  // namespace
}  // namespace vt
