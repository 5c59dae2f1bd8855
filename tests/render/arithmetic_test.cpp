// The arithmetic as independent choices (render/arithmetic.h): the named points are data in one
// file, every point round-trips through a model file, version 1 model files still read, and no
// model file may allow more than the specification.

#include "render/arithmetic.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

// A point no implementation has a name for: a member other than the default in every family.
Arithmetic unnamedPoint() {
  Arithmetic a;
  a.fusedViewport = true;
  a.coverage = {CoverageRule::kSnappedEdges, 6, SnapRounding::kFloor, false, false};
  a.planeSetup = PlaneSetup::kLowestVertex;
  a.planeEvaluation = PlaneEvaluation::kQuadStepped;
  a.perspective = Perspective::kDivided;
  a.depth = {false, Z24Conversion::kTruncated};
  a.log2 = Log2Form::kPolynomialUnfused;
  a.filter = {FilterWeights::kFloat, true, true};
  a.texelConversion = UnormConversion::kDivided;
  a.flushDenormals = true;
  return a;
}

TEST(Arithmetic, NamedPointsAreDistinctAndFoundByName) {
  EXPECT_EQ(arithmeticPointNames(), (std::vector<std::string>{"exact", "llvmpipe", "softpipe"}));
  for (const std::string& name : arithmeticPointNames()) {
    EXPECT_EQ(arithmeticPointName(arithmeticPoint(name)), name);
    EXPECT_EQ(arithmeticLabel(arithmeticPoint(name)), name);
  }
  EXPECT_FALSE(arithmeticPoint("llvmpipe") == arithmeticPoint("softpipe"));
  EXPECT_EQ(arithmeticPointName(unnamedPoint()), "");
  EXPECT_EQ(arithmeticLabel(unnamedPoint()), "calibrated");
  EXPECT_TRUE(arithmeticPoint("exact") == Arithmetic{});
  try {
    (void)arithmeticPoint("nvidia");
    ADD_FAILURE() << "accepted an unknown point";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("arithmetic 'nvidia' is not one of exact, llvmpipe, softpipe"));
  }
}

TEST(Arithmetic, DescribesEveryFamily) {
  const std::string text = describe(unnamedPoint());
  for (const char* line :
       {"viewport: fused\n", "coverage: snapped_edges, 6 bits, floor, right and top edges in\n",
        "plane_setup: lowest_vertex\n", "plane_evaluation: quad_stepped\n",
        "perspective: divided\n", "depth: as interpolated, Z24 truncated\n",
        "log2: polynomial_unfused\n", "filter: float, fused lerp, fused position\n",
        "texel_conversion: divided\n", "denormals: flushed\n"})
    EXPECT_THAT(text, HasSubstr(line));
  Arithmetic snapped = unnamedPoint();
  snapped.planePositions = PlanePositions::kSnapped;
  EXPECT_THAT(describe(snapped),
              HasSubstr("plane_setup: lowest_vertex, through the positions snapped to the "
                        "coverage's grid\n"));
}

TEST(Arithmetic, EveryPointRoundTripsThroughAModelFile) {
  test::ScratchDirectory dir;
  std::vector<Arithmetic> points = {unnamedPoint()};
  for (const std::string& name : arithmeticPointNames()) points.push_back(arithmeticPoint(name));
  for (const Arithmetic& a : points) {
    const PrecisionModel model = pinnedModel(a, "m");
    std::ofstream(dir / "m.json") << modelJson(model);
    EXPECT_EQ(readModelFile(dir / "m.json"), model) << describe(a);
  }
}

// A version 1 file names a point, and its log2 and filter a member (or "bounded").
TEST(Arithmetic, VersionOneModelFilesStillRead) {
  test::ScratchDirectory dir;
  nlohmann::json v1 = nlohmann::json::parse(modelJson(llvmpipeModel()));
  v1["format"] = "vt-precision-model-1";
  v1["arithmetic"] = "llvmpipe";
  v1["log2"] = "llvmpipe";
  v1["filter"] = "llvmpipe_8bit";
  std::ofstream(dir / "v1.json") << v1.dump();
  EXPECT_EQ(readModelFile(dir / "v1.json"), llvmpipeModel());
  // An exact arithmetic with llvmpipe's filter: the filter member is taken from the file.
  v1["arithmetic"] = "exact";
  v1["log2"] = "ieee";
  std::ofstream(dir / "v1.json") << v1.dump();
  const PrecisionModel mixed = readModelFile(dir / "v1.json");
  EXPECT_EQ(mixed.arithmetic.filter.weights, FilterWeights::kFixedPoint8);
  EXPECT_EQ(mixed.arithmetic.log2, Log2Form::kLibm);
  EXPECT_EQ(mixed.arithmetic.planeEvaluation, PlaneEvaluation::kUnfused);
}

// gl45 itself is the widest model; each bound beyond it is named with its section.
TEST(Arithmetic, NoModelIsWiderThanTheSpecification) {
  EXPECT_TRUE(excessesOverGl45(gl45Model()).empty());
  for (const char* name : {"exact", "llvmpipe", "softpipe"})
    EXPECT_TRUE(excessesOverGl45(namedModel(name)).empty()) << name;
  const auto only = [](const PrecisionModel& m) {
    const std::vector<Gl45Excess> excesses = excessesOverGl45(m);
    EXPECT_EQ(excesses.size(), 1u);
    return excesses.empty() ? std::string() : excesses.front().parameter;
  };
  PrecisionModel m = gl45Model();
  m.subpixelBits = 3;
  EXPECT_EQ(only(m), "subpixel_bits");
  m = gl45Model();
  m.depthUlps = 84.5;
  EXPECT_EQ(only(m), "depth");
  m = gl45Model();
  m.attributeUlps = 21;
  EXPECT_EQ(only(m), "attributes");
  m = gl45Model();
  m.log2Ulps = 3.5;
  EXPECT_EQ(only(m), "log2");
  m = gl45Model();
  m.sqrtUlps = 5;
  EXPECT_EQ(only(m), "sqrt");
  m = gl45Model();
  m.arithmeticUlps = 1.5;
  EXPECT_EQ(only(m), "arithmetic");
  m = gl45Model();
  m.subTexelBits = 4;  // a 4-bit weight filter
  EXPECT_EQ(only(m), "filter");
  EXPECT_THAT(beyondGl45(m), HasSubstr("GL_LINEAR sub-texel bits 4.000000 beyond the "
                                       "specification's 7.000000 (GL 4.5 core, section 8.14.2"));
  m = gl45Model();
  m.filterErrorUnits = 331;  // GL_LINEAR drawn as nearest
  EXPECT_EQ(only(m), "filter");
  // A pinned filter carries no bound to exceed.
  m = llvmpipeModel();
  m.filterErrorUnits = 331;
  EXPECT_TRUE(excessesOverGl45(m).empty());
}

// A comparison with NaN is false: a bound that is not a finite number is never within the
// specification's, pinned or not, and neither is a negative one.
TEST(Arithmetic, ABoundThatIsNotAFiniteNumberIsBeyondTheSpecification) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::pair<double PrecisionModel::*, const char*> fields[] = {
      {&PrecisionModel::depthUlps, "depth"},        {&PrecisionModel::attributeUlps, "attributes"},
      {&PrecisionModel::log2AbsoluteError, "log2"}, {&PrecisionModel::log2Ulps, "log2"},
      {&PrecisionModel::sqrtUlps, "sqrt"},          {&PrecisionModel::arithmeticUlps, "arithmetic"},
      {&PrecisionModel::filterErrorUnits, "filter"}};
  for (const auto& [field, parameter] : fields)
    for (const PrecisionModel& base : {gl45Model(), llvmpipeModel()})
      for (const double value : {nan, inf, -1.0}) {
        PrecisionModel m = base;
        m.*field = value;
        const std::vector<Gl45Excess> excesses = excessesOverGl45(m);
        ASSERT_FALSE(excesses.empty()) << parameter << " " << value << " " << base.name;
        EXPECT_EQ(excesses.front().parameter, parameter) << value << " " << base.name;
        if (!std::isfinite(value)) {
          EXPECT_THAT(excesses.front().text, HasSubstr("not a finite number")) << parameter;
        }
      }
}

}  // namespace
}  // namespace vt
