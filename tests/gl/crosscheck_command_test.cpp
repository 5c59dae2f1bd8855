// `vt crosscheck` in CI: every named scene with both renderers on the driver at hand; on llvmpipe
// every pixel must be identical, and the summary records the settings results depend on.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "cli/run_command.h"
#include "openarena_data.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

// Mesa's other software rasterizer for the commands this process starts (each test runs in a
// process of its own): softpipe, at the GL version the renderer asks for.
void useSoftpipe() {
  ::setenv("GALLIUM_DRIVER", "softpipe", 1);
  ::setenv("MESA_GL_VERSION_OVERRIDE", "4.5", 1);
  ::setenv("MESA_GLSL_VERSION_OVERRIDE", "450", 1);
}

TEST(CrosscheckCommand, EveryScenePassesAndTheSummaryRecordsTheSettings) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "-o", (dir / "out").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("0 unexplained; ambiguous fraction 0.0000, colour width "
                                    "0.0000/255, 1.0000 levels, 1.0000 pages: passed"));
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["passed"], true);
  EXPECT_EQ(summary["frames"].size(), 16u);  // eight scenes, two modes
  EXPECT_EQ(summary["settings"]["LP_NUM_THREADS"], "2");
  EXPECT_TRUE(summary["settings"].contains("GALLIVM_PERF"));
  EXPECT_TRUE(summary["settings"].contains("GALLIUM_OVERRIDE_CPU_CAPS"));
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos &&
      summary["model"] == "llvmpipe") {
    EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  }
  // A pinned model's verdict is one value per pixel: in every frame, width 0, one level, one page.
  for (const nlohmann::json& frame : summary["frames"]) {
    EXPECT_GT(frame["covered"].get<uint64_t>(), 0u) << frame["scene"];
    EXPECT_EQ(frame["mean_color_width"].get<double>(), 0.0) << frame["scene"];
    EXPECT_EQ(frame["mean_candidate_levels"].get<double>(), 1.0) << frame["scene"];
    EXPECT_EQ(frame["mean_candidate_pages"].get<double>(), 1.0) << frame["scene"];
  }
  EXPECT_TRUE(
      std::filesystem::exists(dir / "out" / "horizon-texelfetch-trilinear-need32-classes.png"));
}

// A flythrough of the real map q3dm6ish (retextured and built here; OpenArena fetched by
// scripts/fetch-openarena.sh, VT_OPENARENA_DIR): on llvmpipe every pixel identical.
TEST(CrosscheckCommand, Q3dm6ishFlythroughPasses) {
  VT_REQUIRE_OPENARENA(packages);
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(test::retextureAndBuildQ3dm6ish(*packages, dir.path()));
  const std::string out = (dir / "q3").string();
  const auto result = test::runCommand(
      VT_EXECUTABLE,
      {"crosscheck", (dir / "q3.vt").string(), "--mesh", out + "/q3dm6ish.obj", "--path",
       out + "/q3dm6ish.path.json", "--every", "48", "-o", (dir / "cc").string()},
      dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr("0 unexplained; ambiguous fraction 0.0000, colour width "
                                    "0.0000/255, 1.0000 levels, 1.0000 pages: passed"));
  std::ifstream in(dir / "cc" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["frames"].size(), 40u);  // 40 keyframes 24 apart: 20 frames, two modes
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos &&
      summary["model"] == "llvmpipe") {
    EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  }

  // `vt render` draws the same frame with either backend from one command line: by default both
  // from the levels an 8192^2 cache texture holds (the map's pages do not all fit).
  std::string cacheLine;
  for (const std::string backend : {"gl", "oracle"}) {
    const auto rendered = test::runCommand(
        VT_EXECUTABLE,
        {"render", (dir / "q3.vt").string(), "--mesh", out + "/q3dm6ish.obj", "--camera",
         "6.9088,0.6604,13.4112:7.6519,0.6604,14.0803:73.74", "--size", "160x100", "--backend",
         backend, "--profile", "llvmpipe", "-o", (dir / (backend + ".png")).string()},
        dir.path());
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
    const std::string line = rendered.out.substr(0, rendered.out.find('\n'));
    EXPECT_THAT(line, HasSubstr("cache state: "));
    if (cacheLine.empty()) cacheLine = line;
    EXPECT_EQ(line, cacheLine) << backend;
  }
  if (summary["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos &&
      summary["model"] == "llvmpipe") {
    EXPECT_EQ(test::readBytes(dir / "gl.png"), test::readBytes(dir / "oracle.png"));
  }

  // The same map on llvmpipe generated for SSE2 alone (no FMA, 8-bit GL_LINEAR with floored
  // lerps), an implementation no code of the oracle names: under the model `vt calibrate`
  // measures there, every pixel identical and nothing ambiguous.
  ::setenv("GALLIUM_OVERRIDE_CPU_CAPS", "sse2", 1);
  const auto calibrated = test::runCommand(
      VT_EXECUTABLE, {"calibrate", "-o", (dir / "variant.json").string()}, dir.path());
  ASSERT_EQ(calibrated.exitCode, 0) << calibrated.err;
  const auto variant =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "q3.vt").string(), "--mesh", out + "/q3dm6ish.obj",
                        "--path", out + "/q3dm6ish.path.json", "--every", "192", "--model",
                        (dir / "variant.json").string(), "-o", (dir / "variant").string()},
                       dir.path());
  ::unsetenv("GALLIUM_OVERRIDE_CPU_CAPS");
  ASSERT_EQ(variant.exitCode, 0) << variant.out << variant.err;
  std::ifstream variantIn(dir / "variant" / "summary.json");
  const auto variantSummary = nlohmann::json::parse(variantIn);
  EXPECT_EQ(variantSummary["model"], "calibrated");
  EXPECT_EQ(variantSummary["totals"]["identical"], variantSummary["totals"]["pixels"]);
  EXPECT_EQ(variantSummary["totals"]["ambiguous_fraction"].get<double>(), 0.0);

  // The same map on softpipe under gl45, every 192nd frame: nothing unexplained.
  useSoftpipe();
  const auto soft =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "q3.vt").string(), "--mesh", out + "/q3dm6ish.obj",
                        "--path", out + "/q3dm6ish.path.json", "--every", "192", "--model", "gl45",
                        "-o", (dir / "soft").string()},
                       dir.path());
  std::cout << soft.out;
  ASSERT_EQ(soft.exitCode, 0) << soft.out << soft.err;
  std::ifstream softIn(dir / "soft" / "summary.json");
  const auto softSummary = nlohmann::json::parse(softIn);
  EXPECT_EQ(softSummary["gl_renderer"], "softpipe");
  EXPECT_EQ(softSummary["totals"]["unexplained"], 0u);

  // And under softpipe's own model (auto): every pixel identical, at most a tenth of gl45's
  // ambiguous fraction (the bound; here none).
  const auto own =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "q3.vt").string(), "--mesh", out + "/q3dm6ish.obj",
                        "--path", out + "/q3dm6ish.path.json", "--every", "192", "-o",
                        (dir / "soft-own").string()},
                       dir.path());
  std::cout << own.out;
  ASSERT_EQ(own.exitCode, 0) << own.out << own.err;
  std::ifstream ownIn(dir / "soft-own" / "summary.json");
  const auto ownSummary = nlohmann::json::parse(ownIn);
  EXPECT_EQ(ownSummary["model"], "softpipe");
  EXPECT_EQ(ownSummary["totals"]["identical"], ownSummary["totals"]["pixels"]);
  EXPECT_LE(ownSummary["totals"]["ambiguous_fraction"].get<double>(),
            softSummary["totals"]["ambiguous_fraction"].get<double>() / 10);
}

// Soundness of the gl45 model: llvmpipe conforms to OpenGL 4.5, so every pixel it draws must lie in
// the result sets the oracle computes under gl45 from its own IEEE arithmetic (not llvmpipe's),
// while most pixels' sets hold more than one value. A set too narrow anywhere fails this test.
TEST(CrosscheckCommand, LlvmpipeLiesInsideEveryGl45Set) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  // Every pixel's set (--all-sets), and by default the sets where GL's frame differs: the same
  // verdicts, the ambiguity and widths of the differing pixels alone.
  const auto judged = test::runCommand(VT_EXECUTABLE,
                                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100",
                                        "--model", "gl45", "-o", (dir / "judged").string()},
                                       dir.path());
  ASSERT_EQ(judged.exitCode, 0) << judged.out << judged.err;
  EXPECT_THAT(judged.out, HasSubstr(" pages (of the differing pixels): passed"));
  const auto result =
      test::runCommand(VT_EXECUTABLE,
                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100", "--model",
                        "gl45", "--all-sets", "-o", (dir / "out").string()},
                       dir.path());
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_THAT(result.out, HasSubstr(" 0 unexplained; ambiguous fraction "));
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  const auto judgedSummary = nlohmann::json::parse(std::ifstream(dir / "judged" / "summary.json"));
  const nlohmann::json& totals = summary["totals"];
  const nlohmann::json& judgedTotals = judgedSummary["totals"];
  for (const char* count : {"pixels", "identical", "explained", "unexplained", "explained_by"})
    EXPECT_EQ(judgedTotals[count], totals[count]) << count;
  EXPECT_EQ(totals["sets"], "every pixel");
  EXPECT_EQ(totals["set_pixels"], totals["pixels"]);
  EXPECT_EQ(judgedTotals["sets"], "differing pixels");
  EXPECT_EQ(judgedTotals["set_pixels"].get<uint64_t>(),
            totals["pixels"].get<uint64_t>() - totals["identical"].get<uint64_t>());
  EXPECT_LE(judgedTotals["ambiguous"].get<uint64_t>(), judgedTotals["set_pixels"].get<uint64_t>());
  EXPECT_EQ(summary["model"], "gl45");
  EXPECT_EQ(summary["frames"].size(), 16u);
  EXPECT_EQ(summary["totals"]["unexplained"], 0u);
  // The model leaves room (llvmpipe differs from IEEE arithmetic in places), and says how much.
  EXPECT_GT(summary["totals"]["explained"].get<uint64_t>(), 0u);
  EXPECT_GT(summary["totals"]["ambiguous_fraction"].get<double>(), 0.2);
  EXPECT_LT(summary["totals"]["identical"].get<uint64_t>(),
            summary["totals"]["pixels"].get<uint64_t>());
  // How much: every frame's covered pixels admit more than one colour on average, at most the
  // whole range (the terrain's sets admit every colour: docs/precision-models.md).
  for (const nlohmann::json& record : summary["frames"]) {
    const double width = record["mean_color_width"].get<double>();
    EXPECT_GT(width, 0.0) << record["scene"] << " " << record["mode"];
    EXPECT_TRUE(std::isfinite(width)) << record["scene"];
    EXPECT_LE(width, 255.0) << record["scene"];
    EXPECT_GE(record["mean_candidate_levels"].get<double>(), 1.0) << record["scene"];
    EXPECT_GE(record["mean_candidate_pages"].get<double>(), 1.0) << record["scene"];
    EXPECT_TRUE(std::isfinite(record["mean_candidate_pages"].get<double>())) << record["scene"];
  }
  EXPECT_GT(summary["totals"]["mean_color_width"].get<double>(), 0.0);
  EXPECT_LT(summary["totals"]["mean_color_width"].get<double>(), 255.0);
  EXPECT_GT(summary["totals"]["mean_candidate_levels"].get<double>(), 1.0);
  EXPECT_GT(summary["totals"]["mean_candidate_pages"].get<double>(), 1.0);
}

// A second implementation judged under gl45: softpipe computes differently from the oracle in many
// places (no vertex snapping, another tie rule, Z24 truncated, float filter weights, log2 through
// logf), and every difference must lie in the pixel's set.
TEST(CrosscheckCommand, SoftpipeLiesInsideEveryGl45Set) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  useSoftpipe();
  const auto result = test::runCommand(VT_EXECUTABLE,
                                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100",
                                        "--model", "gl45", "-o", (dir / "out").string()},
                                       dir.path());
  std::cout << result.out;
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["gl_renderer"], "softpipe");
  EXPECT_EQ(summary["model"], "gl45");
  EXPECT_EQ(summary["totals"]["unexplained"], 0u);
  EXPECT_GT(summary["totals"]["explained"].get<uint64_t>(), 0u);
}

// Under its own model (what auto picks for softpipe) the oracle computes softpipe's arithmetic
// (reference/softpipe-arithmetic.md): every pixel of every named scene identical, in both modes.
TEST(CrosscheckCommand, SoftpipeIsBitExactUnderItsModel) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt",
                        {{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  useSoftpipe();
  const auto result = test::runCommand(VT_EXECUTABLE,
                                       {"crosscheck", (dir / "t.vt").string(), "--size", "160x100",
                                        "--all-sets", "-o", (dir / "out").string()},
                                       dir.path());
  std::cout << result.out;
  ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
  std::ifstream in(dir / "out" / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["gl_renderer"], "softpipe");
  EXPECT_EQ(summary["model"], "softpipe");  // auto
  EXPECT_EQ(summary["frames"].size(), 16u);
  EXPECT_EQ(summary["totals"]["identical"], summary["totals"]["pixels"]);
  // Ambiguous only where flushing or keeping denormals changes the value: nowhere here.
  EXPECT_EQ(summary["totals"]["ambiguous_fraction"].get<double>(), 0.0);
}

TEST(CrosscheckCommand, UnknownSceneIsAnError) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(
      dir / "t.vt", {{.pageSize = 16, .border = 1, .levelCount = 3, .channels = 4}, std::nullopt});
  const auto result = test::runCommand(
      VT_EXECUTABLE, {"crosscheck", (dir / "t.vt").string(), "--scenes", "room,moon"}, dir.path());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, HasSubstr("scene 'moon' is not one of"));
}

}  // namespace
}  // namespace vt
