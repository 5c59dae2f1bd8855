// The crosscheck workflows as a library (src/verify/): the verdict, the report's contents, and the
// report written whole or not at all, for scenes drawn on this machine's GL implementation and
// for captures of another renderer (here made with the oracle's API and then altered).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "common/error.h"
#include "format/virtual_texture_reader.h"
#include "render/cache_state.h"
#include "render/precision_model.h"
#include "render/precision_model_file.h"
#include "scene/clip_space_mesh.h"
#include "test_json.h"
#include "test_support.h"
#include "verify/crosscheck_captures.h"
#include "verify/crosscheck_scenes.h"
#include "verify/oracle_conversions.h"
#include "vt/oracle.h"
#include "render/arithmetic_points.h"

namespace vt {
namespace {

constexpr Viewport kViewport{96, 64};

using ::testing::HasSubstr;
using test::readJson;
using test::readText;

void writeTexture(const std::filesystem::path& path) {
  writeSyntheticTexture(path,
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
}

ScenesCheckOptions scenesCheck(const test::ScratchDirectory& dir, const std::string& model) {
  return {dir / "t.vt", namedSceneViews("horizon,grazing"), kViewport, model, dir / "out"};
}

TEST(Crosscheck, ScenesPassUnderTheImplementationsModelAndTheReportHoldsEveryComparison) {
  test::ScratchDirectory dir;
  writeTexture(dir / "t.vt");
  const ScenesCheck check = crosscheckScenes(scenesCheck(dir, "auto"));
  EXPECT_TRUE(check.passed());
  EXPECT_EQ(check.totals.pixels, 2u * 2u * kViewport.width * kViewport.height);  // views x modes
  // On llvmpipe with FMA (CI), auto confirms the llvmpipe model by its fingerprint and every
  // pixel is identical; elsewhere the verdict alone is asserted.
  if (check.renderer.find("llvmpipe") != std::string::npos && __builtin_cpu_supports("fma")) {
    EXPECT_EQ(check.model, "llvmpipe");
    EXPECT_EQ(check.totals.identical, check.totals.pixels);
  }
  const nlohmann::json summary = readJson(dir / "out" / "summary.json");
  EXPECT_EQ(summary["passed"], true);
  EXPECT_EQ(summary["model"], check.model);
  EXPECT_EQ(summary["gl_renderer"], check.renderer);
  ASSERT_EQ(summary["frames"].size(), 4u);
  EXPECT_EQ(summary["frames"][3]["scene"], "grazing");
  EXPECT_EQ(summary["totals"]["pixels"], check.totals.pixels);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "grazing-linear-bilinear-need8-classes.png"));
}

// The exact model has no 8-bit filter weights nor llvmpipe's log2: the same frames fail under it,
// so the verdict depends on the model and is not always "passed".
TEST(Crosscheck, ScenesFailUnderAModelNarrowerThanTheImplementation) {
  test::ScratchDirectory dir;
  writeTexture(dir / "t.vt");
  const ScenesCheck check = crosscheckScenes(scenesCheck(dir, "exact"));
  EXPECT_FALSE(check.passed());
  EXPECT_GT(check.totals.unexplained, 0u);
  EXPECT_EQ(readJson(dir / "out" / "summary.json")["passed"], false);
}

TEST(Crosscheck, AFailureLeavesThePreviousReportAsItWas) {
  test::ScratchDirectory dir;
  writeTexture(dir / "t.vt");
  crosscheckScenes(scenesCheck(dir, "auto"));
  const std::string before = readText(dir / "out" / "summary.json");
  ScenesCheckOptions missing = scenesCheck(dir, "auto");
  missing.texture = dir / "missing.vt";
  const auto refusal = [](const ScenesCheckOptions& options) -> std::string {
    try {
      crosscheckScenes(options);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no InputError";
  };
  EXPECT_THAT(refusal(missing), HasSubstr("missing.vt"));
  ScenesCheckOptions badModel = scenesCheck(dir, "auto");
  badModel.model = (dir / "no-model.json").string();
  EXPECT_THAT(refusal(badModel), HasSubstr("no-model.json"));
  EXPECT_EQ(readText(dir / "out" / "summary.json"), before);
}

// Two captures drawn by the oracle itself under a renderer name that selects gl45, one of them
// then given one wrong pixel, and a manifest that is not a capture.
class CapturesCrosscheck : public ::testing::Test {
 protected:
  void SetUp() override {
    writeTexture(dir_ / "t.vt");
    const VirtualTextureReader reader(dir_ / "t.vt");
    const oracle::Texture texture = oracle::Texture::open(dir_ / "t.vt");
    const oracle::CacheState cache = publicCacheState(cacheOfLevels(reader, -1, 8192));
    std::filesystem::create_directories(dir_ / "captures");
    for (const std::string name : {"horizon", "grazing"}) {
      const NamedScene scene = testScene(name);
      oracle::Capture capture;
      capture.renderer = "a renderer under test";
      capture.texture = dir_ / "t.vt";
      capture.textureIdentity = texture.identity();
      capture.scene =
          oracle::publicScene(toClipSpace(scene.mesh, scene.camera, kViewport), kViewport);
      capture.cache = cache;
      oracle::RenderOptions options = oracle::renderOptions(capture, oracle::Profile::kExact);
      const oracle::Frame frame = oracle::render(texture, capture.scene, cache, options);
      capture.color = frame.color;
      capture.need = frame.need;
      oracle::writeCapture(dir_ / "captures" / (name + ".json"), capture);
      captures_.push_back(capture);
    }
  }

  CapturesCheck check() {
    return crosscheckCaptures({.captures = dir_ / "captures", .output = dir_ / "out"});
  }

  test::ScratchDirectory dir_;
  std::vector<oracle::Capture> captures_;
};

TEST_F(CapturesCrosscheck, CapturesOfTheOraclesOwnFramesPass) {
  const CapturesCheck result = check();
  EXPECT_TRUE(result.passed());
  EXPECT_EQ(result.captures, 2u);
  EXPECT_EQ(result.unreadable, 0u);
  EXPECT_EQ(result.totals.pixels, 2u * kViewport.width * kViewport.height);
  const nlohmann::json summary = readJson(dir_ / "out" / "summary.json");
  EXPECT_EQ(summary["frames"][0]["model"], "gl45");
  EXPECT_NE(readText(dir_ / "out" / "junit.xml").find("tests=\"2\" failures=\"0\" errors=\"0\""),
            std::string::npos);
}

TEST_F(CapturesCrosscheck, OneWrongPixelAndOneUnreadableManifestFailTheCheck) {
  // The middle pixel of "grazing" far from its value: outside every gl45 result set.
  oracle::Capture capture = captures_[1];  // grazing, the first capture by name
  const size_t pixel = (kViewport.height / 2 * kViewport.width + kViewport.width / 2) * 4;
  capture.color[pixel] = static_cast<uint8_t>(capture.color[pixel] ^ 0x80);
  oracle::writeCapture(dir_ / "captures" / "grazing.json", capture);
  std::ofstream(dir_ / "captures" / "zz-not-a-capture.json") << "{\"format\": 1}";

  const CapturesCheck result = check();
  EXPECT_FALSE(result.passed());
  EXPECT_EQ(result.totals.unexplained, 1u);
  EXPECT_EQ(result.captures, 3u);
  EXPECT_EQ(result.unreadable, 1u);
  const nlohmann::json summary = readJson(dir_ / "out" / "summary.json");
  EXPECT_EQ(summary["passed"], false);
  ASSERT_EQ(summary["frames"][0]["unexplained_pixels"].size(), 1u);
  EXPECT_EQ(summary["frames"][0]["unexplained_pixels"][0]["x"], kViewport.width / 2);
  EXPECT_EQ(summary["frames"][0]["unexplained_pixels"][0]["y"], kViewport.height / 2);
  EXPECT_TRUE(summary["frames"][2].contains("error"));
  EXPECT_NE(readText(dir_ / "out" / "junit.xml").find("tests=\"3\" failures=\"1\" errors=\"1\""),
            std::string::npos);
}

// A capture may name its own model file: under --model auto that file judges it (and the summary
// says so), a model given as an option judges every capture, and a capture without one is judged
// by its renderer's shipped model. The model decides the verdict: a frame in llvmpipe's
// arithmetic (8-bit filter weights, its log2) is bit-exact under the llvmpipe model its capture
// names, and fails under exact.
TEST_F(CapturesCrosscheck, ACapturesOwnModelFileJudgesItUnderAuto) {
  std::filesystem::create_directories(dir_ / "models");
  std::ofstream(dir_ / "models" / "llvmpipe.json") << modelJson(llvmpipeModel());
  oracle::Capture capture = captures_[1];  // grazing, the first capture by name
  const oracle::Frame frame =
      oracle::render(oracle::Texture::open(dir_ / "t.vt"), capture.scene, capture.cache,
                     oracle::renderOptions(capture, oracle::Profile::kLlvmpipe));
  capture.color = frame.color;
  capture.need = frame.need;
  capture.model = dir_ / "models" / "llvmpipe.json";
  oracle::writeCapture(dir_ / "captures" / "grazing.json", capture);

  const CapturesCheck automatic = check();
  EXPECT_TRUE(automatic.passed());
  nlohmann::json summary = readJson(dir_ / "out" / "summary.json");
  const nlohmann::json& own = summary["frames"][0];
  EXPECT_EQ(own["capture"], "grazing.json");
  EXPECT_EQ(own["model"], "llvmpipe");
  EXPECT_EQ(own["model_from"], "capture");
  EXPECT_EQ(own["identical"], kViewport.width * kViewport.height);
  EXPECT_EQ(std::filesystem::canonical(own["model_file"].get<std::string>()),
            std::filesystem::canonical(dir_ / "models" / "llvmpipe.json"));
  const nlohmann::json& other = summary["frames"][1];
  EXPECT_EQ(other["model"], "gl45");
  EXPECT_EQ(other["model_from"], "unverified");
  EXPECT_TRUE(other["model_file"].is_null());

  const CapturesCheck option = crosscheckCaptures(
      {.captures = dir_ / "captures", .output = dir_ / "out", .profile = "exact"});
  EXPECT_FALSE(option.passed());
  EXPECT_GT(option.totals.unexplained, 0u) << "llvmpipe's arithmetic is not exact";
  summary = readJson(dir_ / "out" / "summary.json");
  EXPECT_EQ(summary["frames"][0]["model"], "exact");
  EXPECT_EQ(summary["frames"][0]["model_from"], "option");

  // A model file the capture names but that is not there: that capture is unreadable.
  std::filesystem::remove(dir_ / "models" / "llvmpipe.json");
  const CapturesCheck missing = check();
  EXPECT_EQ(missing.unreadable, 1u);
  summary = readJson(dir_ / "out" / "summary.json");
  EXPECT_NE(summary["frames"][0]["error"].get<std::string>().find("llvmpipe.json"),
            std::string::npos);
}

}  // namespace
}  // namespace vt
