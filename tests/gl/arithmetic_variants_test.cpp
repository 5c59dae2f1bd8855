// Calibration on implementations the oracle was not written for (docs/precision-models.md):
// Mesa's llvmpipe with options that change its arithmetic while staying conformant, and with
// options that break a rule. No code or data of the project names these variants: each is a
// process of its own with the option set before the driver loads, `vt calibrate` measures it
// family by family, and `vt crosscheck` judges the named scenes under what it measured.
//
//   GALLIUM_OVERRIDE_CPU_CAPS=sse4.1   llvmpipe generated without FMA: unfused viewport, planes
//                                      and log2 polynomial
//   GALLIVM_PERF=no_aos_sampling       GL_LINEAR in float with fused lerps
//   both                               GL_LINEAR in float with unfused lerps, and no FMA
//   GALLIUM_OVERRIDE_CPU_CAPS=sse2     llvmpipe generated for SSE2 alone: 8-bit GL_LINEAR whose
//                                      lerp products are floored, not rounded
//   DRAW_USE_LLVM=0                    vertices transformed by the draw module's C code: an
//                                      unfused viewport beside fused planes and log2
//   GALLIUM_NOSSE=1                    x87 code: expressions in extended precision, which no
//                                      member reproduces; bounded by what was measured
//   LP_PERF=no_linear                  GL_LINEAR sampled as nearest: breaks section 8.14.2
//   LP_PERF=no_depth                   no depth test: breaks section 17.3
//   4-bit GL_LINEAR weights            every textureLod replaced, through Mesa's own shader
//                                      replacement (MESA_SHADER_READ_PATH), by a filter whose
//                                      weights have 4 fractional bits: beyond dEQP's 7 (8.14.2)

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// name=value pairs, set for the runs of one test (each test is a process of its own).
using Environment = std::vector<std::pair<std::string, std::string>>;

class ArithmeticVariant : public ::testing::Test {
 protected:
  void SetUp() override {
    writeSyntheticTexture(dir_ / "t.vt",
                          {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  }

  test::CommandResult run(const Environment& environment, const std::vector<std::string>& args) {
    for (const auto& [name, value] : environment) ::setenv(name.c_str(), value.c_str(), 1);
    const test::CommandResult result = test::runCommand(VT_EXECUTABLE, args, dir_.path());
    for (const auto& [name, value] : environment) ::unsetenv(name.c_str());
    return result;
  }

  test::CommandResult calibrate(const Environment& environment) {
    return run(environment, {"calibrate", "-o", (dir_ / "model.json").string()});
  }

  nlohmann::json crosscheck(const Environment& environment, const std::string& model,
                            std::string* err = nullptr) {
    const std::string out = (dir_ / ("out-" + model.substr(model.rfind('/') + 1))).string();
    const test::CommandResult result =
        run(environment, {"crosscheck", (dir_ / "t.vt").string(), "--size", "160x100", "--model",
                          model, "--all-sets", "-o", out});
    std::cout << result.out << result.err;
    EXPECT_EQ(result.exitCode, 0) << result.err;
    if (err) *err = result.err;
    std::ifstream in(std::filesystem::path(out) / "summary.json");
    return in ? nlohmann::json::parse(in) : nlohmann::json::object();
  }

  // A conformant variant: every family pinned, the crosscheck under the calibrated model bit
  // for bit with nothing ambiguous, and `auto` (which fingerprints the shipped models, none of
  // which this variant is) judging it under gl45 without failing it.
  void expectPinnedAndExact(const Environment& environment) {
    const test::CommandResult calibration = calibrate(environment);
    std::cout << calibration.out;
    ASSERT_EQ(calibration.exitCode, 0) << calibration.err;
    EXPECT_THAT(calibration.out, Not(HasSubstr("[bounded]")));
    const PrecisionModel model = readModelFile(dir_ / "model.json");
    EXPECT_TRUE(model.pinned());
    const nlohmann::json exact = crosscheck(environment, (dir_ / "model.json").string());
    EXPECT_EQ(exact["totals"]["identical"], exact["totals"]["pixels"]);
    EXPECT_EQ(exact["totals"]["ambiguous_fraction"].get<double>(), 0.0);
    std::string err;
    const nlohmann::json automatic = crosscheck(environment, "auto", &err);
    EXPECT_EQ(automatic["model"], "gl45");
    EXPECT_EQ(automatic["totals"]["unexplained"], 0u);
    EXPECT_THAT(err, HasSubstr("reproduces none of the pinned models"));
  }

  test::ScratchDirectory dir_;
};

TEST_F(ArithmeticVariant, WithoutFmaEveryFamilyIsPinnedAndTheCrosscheckIsExact) {
  expectPinnedAndExact({{"GALLIUM_OVERRIDE_CPU_CAPS", "sse4.1"}});
  const PrecisionModel model = readModelFile(dir_ / "model.json");
  EXPECT_EQ(model.arithmetic.planeEvaluation, PlaneEvaluation::kUnfused);
  EXPECT_EQ(model.arithmetic.log2, Log2Form::kPolynomialUnfused);
  EXPECT_FALSE(model.arithmetic.fusedViewport);
}

TEST_F(ArithmeticVariant, FloatFilteringIsPinnedAndTheCrosscheckIsExact) {
  expectPinnedAndExact({{"GALLIVM_PERF", "no_aos_sampling"}});
  const PrecisionModel model = readModelFile(dir_ / "model.json");
  EXPECT_EQ(model.arithmetic.filter.weights, FilterWeights::kFloat);
  EXPECT_TRUE(model.arithmetic.filter.fusedLerp);
}

TEST_F(ArithmeticVariant, FloatFilteringWithoutFmaIsPinnedAndTheCrosscheckIsExact) {
  expectPinnedAndExact(
      {{"GALLIUM_OVERRIDE_CPU_CAPS", "sse4.1"}, {"GALLIVM_PERF", "no_aos_sampling"}});
  const PrecisionModel model = readModelFile(dir_ / "model.json");
  EXPECT_EQ(model.arithmetic.filter.weights, FilterWeights::kFloat);
  EXPECT_FALSE(model.arithmetic.filter.fusedLerp);
}

TEST_F(ArithmeticVariant, FlooredFixedPointLerpsArePinnedAndTheCrosscheckIsExact) {
  expectPinnedAndExact({{"GALLIUM_OVERRIDE_CPU_CAPS", "sse2"}});
  const PrecisionModel model = readModelFile(dir_ / "model.json");
  EXPECT_EQ(model.arithmetic.filter.weights, FilterWeights::kFixedPoint8);
  EXPECT_EQ(model.arithmetic.filter.lerpRounding, LerpRounding::kFloor);
}

TEST_F(ArithmeticVariant, VerticesOutsideTheJitArePinnedAndTheCrosscheckIsExact) {
  // Without LLVM for vertices, llvmpipe offers OpenGL 3.3 unless told otherwise.
  expectPinnedAndExact({{"DRAW_USE_LLVM", "0"},
                        {"MESA_GL_VERSION_OVERRIDE", "4.5"},
                        {"MESA_GLSL_VERSION_OVERRIDE", "450"}});
  EXPECT_FALSE(readModelFile(dir_ / "model.json").arithmetic.fusedViewport);
}

// Extended precision is conformant (GLSL 4.50 section 4.7.1 allows more precision), but no
// member of the families computes it: calibration bounds it by what it measured, within gl45,
// and the crosscheck under that model passes with fewer ambiguous pixels than under gl45.
TEST_F(ArithmeticVariant, ExtendedPrecisionIsBoundedWithinGl45AndPasses) {
  const Environment nosse = {{"GALLIUM_NOSSE", "1"}};
  const test::CommandResult calibration = calibrate(nosse);
  std::cout << calibration.out;
  ASSERT_EQ(calibration.exitCode, 0) << calibration.err;
  EXPECT_THAT(calibration.out, HasSubstr("[bounded]"));
  const PrecisionModel model = readModelFile(dir_ / "model.json");
  EXPECT_FALSE(model.pinned());
  EXPECT_EQ(beyondGl45(model), "");
  const nlohmann::json measured = crosscheck(nosse, (dir_ / "model.json").string());
  EXPECT_EQ(measured["totals"]["unexplained"], 0u);
  const nlohmann::json loose = crosscheck(nosse, "gl45");
  EXPECT_EQ(loose["totals"]["unexplained"], 0u);
  EXPECT_LE(measured["totals"]["ambiguous_fraction"].get<double>(),
            loose["totals"]["ambiguous_fraction"].get<double>());
}

// A rule broken is not calibrated into a model: exit 1, the rule and its section named, and no
// model file.
void expectRefused(const test::CommandResult& calibration, const std::filesystem::path& model,
                   const std::string& rule) {
  EXPECT_EQ(calibration.exitCode, 1) << calibration.out;
  EXPECT_THAT(calibration.err, HasSubstr("breaks a rule: " + rule));
  EXPECT_THAT(calibration.err, HasSubstr("no model written"));
  EXPECT_FALSE(std::filesystem::exists(model));
}

TEST_F(ArithmeticVariant, NearestSamplingForLinearIsRefusedNamingTheRule) {
  const test::CommandResult calibration = calibrate({{"LP_PERF", "no_linear"}});
  expectRefused(calibration, dir_ / "model.json", "GL_LINEAR");
  EXPECT_THAT(calibration.err, HasSubstr("section 8.14.2"));
}

TEST_F(ArithmeticVariant, NoDepthTestIsRefusedNamingTheRule) {
  const test::CommandResult calibration = calibrate({{"LP_PERF", "no_depth"}});
  expectRefused(calibration, dir_ / "model.json", "depth test (GL 4.5 core, section 17.3");
  EXPECT_THAT(calibration.err, HasSubstr("pixels of the overlap show a far quad"));
}

// Every fragment shader of `dump` that samples with textureLod, rewritten so that it samples
// through a filter with weights of 4 fractional bits, into `replace` under the same name (Mesa
// reads a replacement by the SHA-1 of the source it replaces).
int writeFourBitFilterShaders(const std::filesystem::path& dump,
                              const std::filesystem::path& replace) {
  const std::string filter = R"(
vec4 vtFourBitLinear(sampler2D s, vec2 u, float lod) {
  ivec2 size = textureSize(s, 0);
  vec2 x = u * vec2(size) - 0.5;
  vec2 base = floor(x);
  vec2 f = floor((x - base) * 16.0) / 16.0;
  ivec2 i = ivec2(base), m = size - 1;
  vec4 c00 = texelFetch(s, clamp(i, ivec2(0), m), 0);
  vec4 c10 = texelFetch(s, clamp(i + ivec2(1, 0), ivec2(0), m), 0);
  vec4 c01 = texelFetch(s, clamp(i + ivec2(0, 1), ivec2(0), m), 0);
  vec4 c11 = texelFetch(s, clamp(i + ivec2(1, 1), ivec2(0), m), 0);
  return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}
)";
  std::filesystem::create_directories(replace);
  int rewritten = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dump)) {
    if (entry.path().filename().string().rfind("FS_", 0) != 0) continue;
    std::string source = test::slurp(entry.path());
    if (source.find("textureLod(") == std::string::npos) continue;
    // After the directives at the top (#version), the filter; then every textureLod through it.
    std::istringstream lines(source);
    std::string line, head, body;
    bool inHead = true;
    while (std::getline(lines, line)) {
      inHead = inHead && (line.empty() || line[0] == '#');
      (inHead ? head : body) += line + "\n";
    }
    for (size_t at = body.find("textureLod("); at != std::string::npos;
         at = body.find("textureLod(", at))
      body.replace(at, std::string("textureLod(").size(), "vtFourBitLinear(");
    std::ofstream(replace / entry.path().filename()) << head << filter << body;
    ++rewritten;
  }
  return rewritten;
}

// A test-only implementation: llvmpipe whose GL_LINEAR has 4-bit weights. `vt calibrate` refuses
// it naming GL_LINEAR and section 8.14.2; the crosscheck catches it under llvmpipe's pinned model
// and under gl45 (whose sets are narrower than its error on magnified surfaces).
TEST_F(ArithmeticVariant, FourBitFilterWeightsAreRefusedNamingTheRule) {
  const std::filesystem::path dump = dir_ / "dump", replace = dir_ / "replace";
  std::filesystem::create_directories(dump);
  const Environment dumping = {{"MESA_SHADER_DUMP_PATH", dump.string()}};
  ASSERT_EQ(calibrate(dumping).exitCode, 0);
  crosscheck(dumping, "llvmpipe");
  std::filesystem::remove(dir_ / "model.json");
  ASSERT_GE(writeFourBitFilterShaders(dump, replace), 2);  // the probes' and the renderer's
  const Environment fourBit = {{"MESA_SHADER_READ_PATH", replace.string()}};
  const test::CommandResult calibration = calibrate(fourBit);
  expectRefused(calibration, dir_ / "model.json", "GL_LINEAR");
  EXPECT_THAT(calibration.err, HasSubstr("section 8.14.2"));
  for (const std::string model : {"llvmpipe", "gl45"}) {
    const test::CommandResult caught =
        run(fourBit, {"crosscheck", (dir_ / "t.vt").string(), "--size", "160x100", "--model",
                      model, "-o", (dir_ / ("four-bit-" + model)).string()});
    EXPECT_EQ(caught.exitCode, 1) << model << "\n" << caught.out;
    EXPECT_THAT(caught.out, HasSubstr("need filter widened")) << model;
  }
}

// On the implementation the shipped model was written from, `auto` confirms it by its
// fingerprint and judges bit for bit.
TEST_F(ArithmeticVariant, AutoConfirmsTheShippedModelByItsFingerprint) {
  std::string err;
  const nlohmann::json summary = crosscheck({}, "auto", &err);
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") == std::string::npos ||
      !__builtin_cpu_supports("fma"))
    GTEST_SKIP() << "not llvmpipe with FMA";
  EXPECT_EQ(summary["model"], "llvmpipe");
  EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  EXPECT_EQ(err, "");
}

}  // namespace
}  // namespace vt
