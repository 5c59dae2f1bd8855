// The power of the check: the GL path's real fragment shader with one bug planted at a time (a
// textual change of the shader source made here, never in the shipped shader), drawn on llvmpipe
// and judged by the oracle. Under the pinned llvmpipe model every bug must be caught, with the
// right parameter named; under gl45 every bug the specification forbids must be caught, and the
// ones it allows are listed (docs/precision-models.md, "Planted bugs"). The same bugs drawn on
// llvmpipe generated without FMA (GALLIUM_OVERRIDE_CPU_CAPS=sse4.1, an implementation no code of
// the oracle names) must be caught under the model `vt calibrate` measures there, as under
// llvmpipe's.

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "build/synthetic_texture.h"
#include "calibrate/calibration.h"
#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "gl/virtual_texture_program.h"
#include "random_triangles.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "render/frame_comparison.h"
#include "resident_pages.h"
#include "test_support.h"

namespace vt {
namespace {

struct PlantedBug {
  const char* name;
  const char* find;     // in the real fragment shader source, exactly once
  const char* replace;  // the bug
  int reason;           // the parameter the llvmpipe model must name (ResultReason bit)
  bool allowedByGl45;   // whether gl45 may let it pass, and why (docs/precision-models.md)
};

// clang-format off
const PlantedBug kBugs[] = {
    {"HalfTexelOffset", "precise vec2 texel = origin + inside * float(p.pageSize);",
     "precise vec2 texel = origin + inside * float(p.pageSize) + vec2(0.5, 0.5);", 4, false},
    {"BorderOffByOne", "vint(entry.x) * stored + p.border, vint(entry.y) * stored + p.border",
     "vint(entry.x) * stored + p.border - 1, vint(entry.y) * stored + p.border - 1", 4, false},
    {"TrilinearWeightReversed", "precise vec4 color = c0.color + (c1.color - c0.color) * weight;",
     "precise vec4 color = c1.color + (c0.color - c1.color) * weight;", 4, false},
    {"NeedLevelFloor", "vint vtNeededLevel(vfloat lod) { return vint(ceil(lod)); }",
     "vint vtNeededLevel(vfloat lod) { return vint(floor(lod)); }", 3, false},
    {"NoClampOfOneToLastPage",
     "return ivec2(vint(vtClampOrZero(floor(scaled.x), last)),\n"
     "               vint(vtClampOrZero(floor(scaled.y), last)));",
     "return ivec2(vint(floor(scaled.x)), vint(floor(scaled.y)));", 2, false},
    {"IndirectionAtOwnLevel", "vint i = vint(entry.z);", "vint i = level;", 4, false},
    {"BilinearWeightsFourBits", "precise vec2 f = t - base;",
     "precise vec2 f = floor((t - base) * 16.0) / 16.0;", 4, false},
    {"LodFromSumOfLengths", "precise vfloat eMax = sqrt(larger);",
     "precise vfloat eMax = sqrt(ex) + sqrt(ey);", 3, false},
    // Coarse derivatives written out (llvmpipe's dFdxCoarse returns what its dFdxFine returns in
    // these frames): the lower row's dFdx and the left column's dFdy for the whole quad.
    {"CoarseDerivatives", "dFdxFine(vUV), dFdyFine(vUV)",
     "dFdxFine(vUV) - (((int(gl_FragCoord.y) & 1) == 1) ? dFdyFine(dFdxFine(vUV)) : vec2(0.0)), "
     "dFdyFine(vUV) - (((int(gl_FragCoord.x) & 1) == 1) ? dFdxFine(dFdyFine(vUV)) : vec2(0.0))",
     3, false},  // GLSL 4.50, 8.14.1: dFdxFine differences the fragment's own row
};
// clang-format on

std::string plant(const PlantedBug& bug) {
  std::string source = virtualTextureFragmentSource();
  const size_t at = source.find(bug.find);
  EXPECT_NE(at, std::string::npos) << bug.name << ": the shader source changed; update the bug";
  EXPECT_EQ(source.find(bug.find, at + 1), std::string::npos) << bug.name << ": found twice";
  if (at != std::string::npos) source.replace(at, std::string(bug.find).size(), bug.replace);
  return source;
}

// Magnified, minified and grazing triangles, a background quad with s and t exactly 0 and 1 at
// its corners, and a quad whose coordinates run past 1 (the shader clamps them to exactly 1.0).
ClipSpaceMesh scene() {
  std::mt19937 random(11);
  ClipSpaceMesh mesh;
  const auto quad = [&](std::array<glm::vec4, 4> p, std::array<glm::vec2, 4> uv) {
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    for (int k = 0; k < 4; ++k) mesh.vertices.push_back({p[k], uv[k]});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  // A ground plane under perspective, near in front, far at the top: every LOD, fractional.
  quad({glm::vec4(-1, -1, 0.1f, 1), {1, -1, 0.1f, 1}, {8, 6, 7.9f, 8}, {-8, 6, 7.9f, 8}},
       {glm::vec2(0.05f, 0.05f), {0.95f, 0.05f}, {0.95f, 0.95f}, {0.05f, 0.95f}});
  test::appendRandomTriangles(mesh, random, 40);
  // Coordinates past 1 in front, in the upper right corner.
  quad(
      {glm::vec4(0.4f, 0.4f, -0.5f, 1), {1, 0.4f, -0.5f, 1}, {1, 1, -0.5f, 1}, {0.4f, 1, -0.5f, 1}},
      {glm::vec2(0.7f, 0.7f), {1.3f, 0.7f}, {1.3f, 1.3f}, {0.7f, 1.3f}});
  quad({glm::vec4(-1, -1, 0.99f, 1), {1, -1, 0.99f, 1}, {1, 1, 0.99f, 1}, {-1, 1, 0.99f, 1}},
       {glm::vec2(0, 0), {1, 0}, {1, 1}, {0, 1}});
  return mesh;
}

struct Verdict {
  uint64_t unexplained = 0;
  std::array<uint64_t, kResultReasons> by{};
};

class PlantedBugs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { ::setenv("LP_NUM_THREADS", "2", 1); }

  // The bug drawn by GL, judged under `model`, in both of the crosscheck's modes.
  Verdict judge(const PlantedBug* bug, const PrecisionModel& model) {
    Verdict verdict;
    for (const bool texelFetch : {true, false}) {
      RenderSettings settings;
      settings.viewport = {160, 120};
      applyModel(settings, model);
      settings.exactFilter = texelFetch;
      settings.trilinear = texelFetch;
      settings.need8 = !texelFetch;
      GlFrameRenderer renderer(*cache_, bug ? plant(*bug) : virtualTextureFragmentSource());
      const ClipSpaceMesh mesh = scene();
      const Frame gl = renderer.render(mesh, settings);
      const Frame oracle = reference::renderFrame(mesh, *cache_, settings);
      const FrameComparison c =
          compareFrames(oracle, gl.color, gl.need, settings.need8);
      verdict.unexplained += c.unexplained;
      for (size_t r = 0; r < verdict.by.size(); ++r) verdict.by[r] += c.unexplainedBy[r];
    }
    return verdict;
  }

  // Whether the fixture draws on a variant of llvmpipe (set before its context is made).
  virtual bool variant() const { return false; }

  void SetUp() override {
    if (variant()) ::setenv("GALLIUM_OVERRIDE_CPU_CAPS", "sse4.1", 1);
    context_ = std::make_unique<HeadlessContext>();
    if (context_->renderer().find("llvmpipe") == std::string::npos ||
        !__builtin_cpu_supports("fma"))
      GTEST_SKIP() << "the planted bugs are drawn on llvmpipe with FMA: " << context_->renderer();
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 16, .border = 2, .levelCount = 5, .channels = 4}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
    // Levels 0..2 resident, every other page of level 3, a few of level 4: the rest falls back
    // to ancestors, so a lookup at the wrong level shows.
    const std::vector<uint64_t> resident = test::pagesFallingBack(2, {2, 7});
    cache_ = std::make_unique<CacheState>(makeCacheState(*reader_, resident, 12, 8));
  }

  test::ScratchDirectory dir_;
  std::unique_ptr<HeadlessContext> context_;
  std::unique_ptr<VirtualTextureReader> reader_;
  std::unique_ptr<CacheState> cache_;
};

// The oracle's result sets under gl45 are the same on every draw of the scene (its quad with
// coordinates past 1 once read texels outside a sampled box, different from draw to draw).
TEST_F(PlantedBugs, TheSetsAreTheSameOnEveryDraw) {
  for (const bool texelFetch : {true, false}) {
    RenderSettings settings;
    settings.viewport = {160, 120};
    applyModel(settings, gl45Model());
    settings.exactFilter = settings.trilinear = texelFetch;
    settings.need8 = !texelFetch;
    const ClipSpaceMesh mesh = scene();
    const Frame first = reference::renderFrame(mesh, *cache_, settings);
    for (int draw = 0; draw < 3; ++draw) {
      const Frame again = reference::renderFrame(mesh, *cache_, settings);
      ASSERT_EQ(first.sets.offsets, again.sets.offsets);
      size_t differ = 0;
      for (size_t k = 0; k < first.sets.alternatives.size(); ++k) {
        const Alternative &a = first.sets.alternatives[k], &b = again.sets.alternatives[k];
        differ += a.triangle != b.triangle || a.levelLo != b.levelLo || a.levelHi != b.levelHi ||
                  a.uvLo != b.uvLo || a.uvHi != b.uvHi || a.colorLo != b.colorLo ||
                  a.colorHi != b.colorHi || a.filterLo != b.filterLo ||
                  a.filterHi != b.filterHi || a.reasons != b.reasons;
      }
      EXPECT_EQ(differ, 0u) << (texelFetch ? "texel fetches" : "GL_LINEAR") << ", draw " << draw;
    }
  }
}

TEST_F(PlantedBugs, TheRealShaderPassesBothModels) {
  EXPECT_EQ(judge(nullptr, llvmpipeModel()).unexplained, 0u);
  EXPECT_EQ(judge(nullptr, gl45Model()).unexplained, 0u);
}

TEST_F(PlantedBugs, EveryBugIsCaughtUnderLlvmpipeAndGl45CatchesWhatTheSpecificationForbids) {
  for (const PlantedBug& bug : kBugs) {
    const Verdict pinned = judge(&bug, llvmpipeModel());
    const Verdict loose = judge(&bug, gl45Model());
    std::printf(
        "planted bug | %-24s | llvmpipe: %7llu unexplained (%s %llu) | gl45: %7llu "
        "unexplained\n",
        bug.name, static_cast<unsigned long long>(pinned.unexplained), reasonName(bug.reason),
        static_cast<unsigned long long>(pinned.by[static_cast<size_t>(bug.reason)]),
        static_cast<unsigned long long>(loose.unexplained));
    EXPECT_GT(pinned.unexplained, 0u) << bug.name;
    EXPECT_GT(pinned.by[static_cast<size_t>(bug.reason)], 0u)
        << bug.name << ": the llvmpipe model should name " << reasonName(bug.reason);
    if (!bug.allowedByGl45) {
      EXPECT_GT(loose.unexplained, 0u) << bug.name << " passes gl45";
    }
  }
}

class PlantedBugsOnAVariant : public PlantedBugs {
 protected:
  bool variant() const override { return true; }
  void TearDown() override { ::unsetenv("GALLIUM_OVERRIDE_CPU_CAPS"); }
};

TEST_F(PlantedBugsOnAVariant, EveryBugIsCaughtUnderTheVariantsCalibratedModel) {
  const calibrate::Calibration calibration = calibrate::calibrate();
  ASSERT_TRUE(calibration.conformant());
  const PrecisionModel model = calibration.model;
  EXPECT_TRUE(model.pinned()) << describe(model.arithmetic);
  EXPECT_FALSE(model.arithmetic == llvmpipeModel().arithmetic);
  EXPECT_EQ(judge(nullptr, model).unexplained, 0u);
  for (const PlantedBug& bug : kBugs) {
    const Verdict calibrated = judge(&bug, model);
    std::printf(
        "planted bug | %-24s | llvmpipe without FMA, calibrated: %7llu unexplained (%s "
        "%llu)\n",
        bug.name, static_cast<unsigned long long>(calibrated.unexplained), reasonName(bug.reason),
        static_cast<unsigned long long>(calibrated.by[static_cast<size_t>(bug.reason)]));
    EXPECT_GT(calibrated.unexplained, 0u) << bug.name;
    EXPECT_GT(calibrated.by[static_cast<size_t>(bug.reason)], 0u)
        << bug.name << ": the calibrated model should name " << reasonName(bug.reason);
  }
}

}  // namespace
}  // namespace vt
