#include "render/precision_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt::reference {
namespace {

using ::testing::HasSubstr;

TEST(PrecisionModel, ShippedModelsPinWhatTheyMeasureAndGl45LeavesTheSpecificationsSlack) {
  EXPECT_TRUE(llvmpipeModel().pinned());
  EXPECT_TRUE(exactModel().pinned());
  // softpipe changes its denormal mode between batches: that alone is free.
  EXPECT_FALSE(softpipeModel().pinned());
  EXPECT_TRUE(softpipeModel().onlyDenormalsFree());
  EXPECT_FALSE(gl45Model().onlyDenormalsFree());
  const PrecisionModel gl45 = gl45Model();
  EXPECT_FALSE(gl45.pinned());
  EXPECT_FALSE(gl45.coveragePinned());
  EXPECT_EQ(gl45.subpixelBits, 4);  // GL 4.5 table 23.53
  EXPECT_EQ(gl45.log2AbsoluteError, 0x1p-21);
  // Every parameter of every shipped model says where its value comes from.
  for (const PrecisionModel& m : {llvmpipeModel(), softpipeModel(), exactModel(), gl45}) {
    for (const char* parameter : {"subpixel_bits", "fill_rule", "depth", "attributes", "log2",
                                  "sqrt", "arithmetic", "filter", "color_conversion", "denormals"})
      EXPECT_FALSE(m.sources.at(parameter).empty()) << m.name << " " << parameter;
  }
  EXPECT_EQ(namedModel("gl45"), gl45);
  EXPECT_THAT([] { namedModel("nvidia"); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("precision model 'nvidia' is not one of")));
  EXPECT_EQ(namedModel("softpipe"), softpipeModel());
  EXPECT_EQ(modelForRenderer("softpipe").name, "softpipe");
  EXPECT_EQ(modelForRenderer("NVIDIA H100/PCIe/SSE2").name, "gl45");
}

TEST(PrecisionModelFile, RoundTripsEveryParameter) {
  test::ScratchDirectory dir;
  PrecisionModel measured = gl45Model();
  measured.name = "measured";
  measured.renderer = "softpipe";
  measured.subpixelBits = 16;
  measured.fillRulePinned = true;
  measured.arithmetic.coverage.subpixelBits = 16;  // a pinned fill rule is the arithmetic's grid
  measured.filterPinned = true;
  measured.arithmetic.filter.fusedLerp = true;
  measured.sources["filter"] = "probe draws";
  PrecisionModel floored = llvmpipeModel();
  floored.name = "floored";
  floored.arithmetic.filter.lerpRounding = LerpRounding::kFloor;
  // The members measured on a GPU, with their parameters.
  PrecisionModel gpu = gl45Model();
  gpu.name = "gpu";
  gpu.filterPinned = true;
  gpu.arithmetic.filter = {.weights = FilterWeights::kFixedPointCorners,
                           .lerpRounding = LerpRounding::kFloor,
                           .coordinateBits = 20,
                           .weightBits = 6,
                           .positionRounding = PositionRounding::kFloor,
                           .output = FilterOutput::kUnorm8};
  gpu.colorPinned = true;
  gpu.arithmetic.colourConversion = {ColourConversionRule::kQuantized, 10, 511};
  gpu.decodingPinned = true;
  gpu.arithmetic.blockDecoding = {
      PaletteRule::kNvidia, PaletteRule::kWeights, {1, 2, 3, 4, 5, 6, 7, 8, 9, 4096}};
  gpu.arithmetic.planePositions = PlanePositions::kSnapped;
  for (const PrecisionModel& m :
       {measured, floored, gpu, llvmpipeModel(), softpipeModel(), exactModel()}) {
    std::ofstream(dir / "m.json") << modelJson(m);
    EXPECT_EQ(readModelFile(dir / "m.json"), m) << m.name;
    EXPECT_EQ(resolveModel((dir / "m.json").string(), "llvmpipe"), m);
  }
  EXPECT_EQ(resolveModel("exact", "softpipe"), exactModel());
  // Every shipped name is a model, never a file of that name.
  EXPECT_EQ(resolveModel("softpipe", "llvmpipe"), softpipeModel());
  EXPECT_EQ(resolveModel("llvmpipe", "softpipe"), llvmpipeModel());
  EXPECT_EQ(resolveModel("gl45", "llvmpipe"), gl45Model());
  // Without a context to fingerprint, a renderer's name is no evidence.
  EXPECT_EQ(resolveModel("auto", "softpipe"), gl45Model());
  EXPECT_EQ(resolveModel("auto", "an unknown GPU"), gl45Model());
}

// Files written before the fixed-point lerp's rounding was a choice all rounded to nearest.
TEST(PrecisionModelFile, AFileWithoutTheLerpRoundingRoundsToNearest) {
  test::ScratchDirectory dir;
  PrecisionModel floored = llvmpipeModel();
  floored.arithmetic.filter.lerpRounding = LerpRounding::kFloor;
  nlohmann::json j = nlohmann::json::parse(modelJson(floored));
  j["arithmetic"]["filter"].erase("lerp_rounding");
  std::ofstream(dir / "old.json") << j.dump();
  EXPECT_EQ(readModelFile(dir / "old.json").arithmetic.filter.lerpRounding, LerpRounding::kNearest);
  EXPECT_EQ(readModelFile(dir / "old.json"), llvmpipeModel());
}

// Writes `json` to `file`; reading it must fail with an error naming the file and `expected`.
void expectRefused(const std::filesystem::path& file, const nlohmann::json& json,
                   const std::string& expected) {
  std::ofstream(file) << json.dump();
  try {
    (void)readModelFile(file);
    ADD_FAILURE() << "accepted: " << expected;
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
    EXPECT_THAT(e.what(), HasSubstr(expected));
  }
}

TEST(PrecisionModelFile, RefusesMalformedFilesNamingTheField) {
  test::ScratchDirectory dir;
  const nlohmann::json good = nlohmann::json::parse(modelJson(gl45Model()));
  const auto refused = [&](const nlohmann::json& json, const std::string& expected) {
    expectRefused(dir / "bad.json", json, expected);
  };
  nlohmann::json j = good;
  j.erase("attribute_ulps");
  refused(j, "field attribute_ulps is missing");
  j = good;
  j["subpixel_bits"] = 99;
  refused(j, "field subpixel_bits is not a whole number from 1 to 16");
  j = good;
  j["filter"] = "magic";
  refused(j, "field filter is 'magic', not one of pinned, bounded");
  j = good;
  j["arithmetic"]["coverage"]["rounding"] = "sideways";
  refused(j,
          "field arithmetic.coverage.rounding is 'sideways', not one of half_even, half_up, "
          "floor, ceil");
  j = good;
  j["arithmetic"]["depth"].erase("z24");
  refused(j, "field arithmetic.depth.z24 is missing");
  j = good;
  j["arithmetic"]["filter"]["lerp_rounding"] = "up";
  refused(j, "field arithmetic.filter.lerp_rounding is 'up', not one of nearest, floor");
  j = good;
  j["arithmetic"]["filter"]["weights"] = "fixed_point_corners";
  refused(j, "field arithmetic.filter.coordinate_bits is missing");
  j = good;
  j["arithmetic"]["block_decoding"]["alpha"] = "weights";
  refused(j, "field arithmetic.block_decoding.alpha_weights is missing");
  j["arithmetic"]["block_decoding"]["alpha_weights"] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 4097};
  refused(j,
          "field arithmetic.block_decoding.alpha_weights[9] is not a whole number from 0 to 4096");
  j = good;
  j["arithmetic"]["block_decoding"]["colour"] = "weights";
  refused(j, "field colour is 'weights', a rule for alpha palettes only");
  j = good;
  j["arithmetic"]["colour_conversion"] = {{"rule", "quantized"}, {"bits", 12}, {"bias", 4096}};
  refused(j, "field arithmetic.colour_conversion.bias is not a whole number from 0 to 4095");
  j["arithmetic"]["colour_conversion"]["bias"] = 2047;
  j["color_conversion"] = "nearest";
  refused(j, "field color_conversion is 'nearest' but the arithmetic's is 'quantized'");
  j = good;
  j["filter_error_units"] = 5;
  refused(j,
          "allows GL_LINEAR error in units of 1/255 5.000000 beyond the specification's "
          "4.000000 (GL 4.5 core, section 8.14.2");
  j = nlohmann::json::parse(modelJson(llvmpipeModel()));
  j["subpixel_bits"] = 6;
  refused(j, "field subpixel_bits is 6 but the pinned coverage snaps to 8 bits");
  j = good;
  j["depth_ulps"] = 85;
  refused(j, "allows depth error in ulps 85.000000 beyond the specification's 84.000000");
  j = good;
  j["depth_ulps"] = -1;
  refused(j, "field depth_ulps is not a number from 0");
  j = good;
  j["format"] = "vt-precision-model-0";
  refused(j,
          "field format is 'vt-precision-model-0', not one of vt-precision-model-2, "
          "vt-precision-model-1");
  j = good;
  j["sub_texel_bits"] = 0;
  refused(j, "field sub_texel_bits is 0 for a bounded filter");
  j = nlohmann::json::parse(modelJson(softpipeModel()));  // scanline spans: no grid to snap to
  j["arithmetic"]["plane_positions"] = "snapped";
  refused(j,
          "field arithmetic.plane_positions is 'snapped' but the coverage (scanline_spans) "
          "snaps no position");
  j["arithmetic"]["plane_positions"] = "rounded";
  refused(j, "field arithmetic.plane_positions is 'rounded', not one of unsnapped, snapped");
  refused(nlohmann::json::array(), "not a JSON object");
  std::ofstream(dir / "bad.json") << "{\"format\": ";
  try {
    (void)readModelFile(dir / "bad.json");
    ADD_FAILURE() << "accepted a truncated file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("not a precision model"));
  }
  EXPECT_THAT([&] { (void)readModelFile(dir / "missing.json"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr((dir / "missing.json").string())));
}

// A field nobody reads would judge under a default the author never chose: each is refused.
TEST(PrecisionModelFile, RefusesUnknownAndMistypedFieldsNamingThem) {
  test::ScratchDirectory dir;
  const nlohmann::json good = nlohmann::json::parse(modelJson(gl45Model()));
  const auto refused = [&](const nlohmann::json& json, const std::string& expected) {
    expectRefused(dir / "bad.json", json, expected);
  };
  nlohmann::json j = good;
  j["attribute_ulp"] = 0;  // misspelt beside the real bound
  refused(j, "field attribute_ulp is not a field of a precision model here");
  j = good;
  j["arithmetic"]["coverage"]["subpixel_bit"] = 8;
  refused(j, "field arithmetic.coverage.subpixel_bit is not a field of a precision model here");
  j = good;
  j["arithmetic"]["depth"]["z32"] = "truncated";
  refused(j, "field arithmetic.depth.z32 is not a field");
  j = good;
  j["arithmetic"]["planes"] = "snapped";
  refused(j, "field arithmetic.planes is not a field");
  // A member's parameter under another member is read by nobody.
  j = good;
  j["arithmetic"]["filter"]["coordinate_bits"] = 21;
  refused(j, "field arithmetic.filter.coordinate_bits is not a field");
  j = good;
  j["arithmetic"]["block_decoding"]["alpha_weights"] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  refused(j, "field arithmetic.block_decoding.alpha_weights is not a field");
  j = good;
  j["arithmetic"]["colour_conversion"] = {{"rule", "nearest"}, {"bits", 12}};
  refused(j, "field arithmetic.colour_conversion.bits is not a field");
  // Known fields of the wrong type.
  j = good;
  j["fill_rule"] = 1;
  refused(j, "field fill_rule is not a string");
  j = good;
  j["arithmetic"]["coverage"]["left_edges_in"] = "yes";
  refused(j, "field arithmetic.coverage.left_edges_in is not true or false");
  j = good;
  j["depth_ulps"] = "4";
  refused(j, "field depth_ulps is not a number from 0");
  j = good;
  j["subpixel_bits"] = 8.5;
  refused(j, "field subpixel_bits is not a whole number from 1 to 16");
  j = good;
  j["sources"] = {{"depth", 3}};
  refused(j, "field sources.depth is not a string");
  // The calibration's evidence: its known fields in their types, nothing else.
  j = good;
  j["calibration"] = {{"gl_renderer", "r"},
                      {"gl_version", "4.5"},
                      {"gl_vendor", "v"},
                      {"point", "p"},
                      {"parameters", nlohmann::json::array()}};
  std::ofstream(dir / "evidence.json") << j.dump();
  EXPECT_EQ(readModelFile(dir / "evidence.json").glVersion, "4.5");
  j["calibration"]["gl_versoin"] = "4.6";
  refused(j, "field calibration.gl_versoin is not a field of a precision model here");
  j["calibration"].erase("gl_versoin");
  j["calibration"]["gl_version"] = 4.5;
  refused(j, "field calibration.gl_version is not a string");
  j["calibration"]["gl_version"] = "4.5";
  j["calibration"]["parameters"] = "all";
  refused(j, "field calibration.parameters is not a list");
}

// Every model file the project ships reads under the strict reader.
TEST(PrecisionModelFile, ReadsTheShippedGpuModels) {
  const std::filesystem::path gpus =
      std::filesystem::path(VT_TEST_SOURCE_DIR) / ".." / "data" / "gpus";
  int models = 0;
  for (const auto& gpu : std::filesystem::directory_iterator(gpus))
    if (std::filesystem::exists(gpu.path() / "model.json")) {
      EXPECT_NO_THROW((void)readModelFile(gpu.path() / "model.json")) << gpu.path();
      ++models;
    }
  EXPECT_GE(models, 1);
}

}  // namespace
}  // namespace vt::reference
