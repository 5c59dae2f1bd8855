// A measured reciprocal chosen, or refused, by the perspective triangles (calibrate/raster_fit.h,
// render/measured_reciprocal.h). llvmpipe's probes are recorded; their reciprocal sweep is then
// replaced by a table one ulp low at every third input, as an implementation whose reciprocal unit
// is not IEEE division would return it.
//   - With llvmpipe's own triangles (drawn with IEEE 1 / q) the table is offered and refused:
//     the triangles choose IEEE, and the model keeps llvmpipe's point.
//   - With the triangles redrawn by the oracle under llvmpipe's arithmetic and that table (what
//     such an implementation draws), the table is chosen and pinned, written beside the model
//     under its checksum, and the model reads back with it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "calibrate/probe_texture.h"
#include "calibrate/raster_fit.h"
#include "capture/probe_files.h"
#include "capture/sweep_files.h"
#include "cli/run_command.h"
#include "gl/headless_context.h"
#include "probes/function_sweeps.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

std::map<std::string, nlohmann::json> fit(const std::filesystem::path& folder,
                                          const std::filesystem::path& model) {
  const test::CommandResult fitted = test::runCommand(
      VT_EXECUTABLE, {"calibrate", "--probes", folder.string(), "-o", model.string()},
      folder.parent_path());
  EXPECT_EQ(fitted.exitCode, 0) << fitted.err;
  const nlohmann::json json = nlohmann::json::parse(test::slurp(model));
  std::map<std::string, nlohmann::json> byName;
  for (const nlohmann::json& p : json["calibration"]["parameters"])
    byName[p["parameter"].get<std::string>()] = p;
  byName["point"] = json["calibration"]["point"];
  return byName;
}

TEST(MeasuredReciprocalFit, ThePerspectiveTrianglesChooseOrRefuseTheTable) {
  {
    const HeadlessContext context;
    if (context.renderer().find("llvmpipe") == std::string::npos ||
        !__builtin_cpu_supports("fma"))
      GTEST_SKIP() << "not llvmpipe with FMA";
  }
  test::ScratchDirectory dir;
  const std::filesystem::path probes = dir / "probes";
  const test::CommandResult recorded = test::runCommand(
      VT_EXECUTABLE, {"calibrate", "--record-probes", probes.string(), "-o", (dir / "here.json").string()},
      dir.path());
  ASSERT_EQ(recorded.exitCode, 0) << recorded.err;

  const calibrate::FunctionSweep& sweep = *calibrate::packSweep("reciprocal");
  std::vector<uint32_t> table = *capture::readSweepResult(probes, sweep);
  for (size_t i = 1; i < table.size(); i += 3) --table[i];  // 1 / x for x > 1: below 1, so > 0.5
  capture::writeSweepResult(probes, sweep, table);

  auto refused = fit(probes, dir / "refused.json");
  EXPECT_FALSE(refused["reciprocal"]["pinned"].get<bool>());
  EXPECT_THAT(refused["reciprocal"]["finding"].get<std::string>(),
              HasSubstr("2796203 of 8388608 differ from IEEE division"));
  EXPECT_THAT(refused["reciprocal"]["finding"].get<std::string>(),
              HasSubstr("is offered to the perspective probes"));
  EXPECT_TRUE(refused["perspective_reciprocal"]["pinned"].get<bool>());
  EXPECT_EQ(refused["perspective_reciprocal"]["chosen"], "ieee");
  EXPECT_EQ(refused["point"], "llvmpipe");
  EXPECT_TRUE(refused["attributes"]["pinned"].get<bool>());

  // The triangles as an implementation with that reciprocal draws them.
  Arithmetic measured = llvmpipeModel().arithmetic;
  measured.reciprocal.table = std::make_shared<const MeasuredReciprocal>(table);
  const calibrate::ProbeTexture texture(4);
  const size_t count = capture::readProbeFolder(probes).count;
  size_t redrawn = 0;
  for (size_t i = 0; i < count; ++i) {
    const capture::ProbeRequest request = capture::readProbeRequest(probes, i);
    if (request.kind != capture::ProbeRequest::Kind::kTriangles ||
        request.interpolation != calibrate::Interpolation::kPerspective)
      continue;
    const Frame frame = calibrate::oracleFrame(request.mesh, texture.texture(), request.viewport,
                                               measured, request.depth);
    capture::ProbeResult result;
    result.raster = {frame.triangle, frame.uv, frame.derivatives, frame.depth};
    capture::writeProbeResult(probes, i, request, result);
    ++redrawn;
  }
  EXPECT_GT(redrawn, 20u);
  auto chosen = fit(probes, dir / "chosen.json");
  EXPECT_TRUE(chosen["perspective_reciprocal"]["pinned"].get<bool>());
  EXPECT_EQ(chosen["perspective_reciprocal"]["chosen"], "measured");
  EXPECT_THAT(chosen["perspective_reciprocal"]["finding"].get<std::string>(),
              HasSubstr("ieee"));
  EXPECT_TRUE(chosen["attributes"]["pinned"].get<bool>());
  EXPECT_EQ(chosen["point"], "");  // no named point has the table
  const std::string checksum = measured.reciprocal.table->checksum();
  EXPECT_TRUE(std::filesystem::exists(dir / reciprocalTableName(checksum)));
  const PrecisionModel model = readModelFile(dir / "chosen.json");
  ASSERT_TRUE(model.arithmetic.reciprocal.table);
  EXPECT_EQ(model.arithmetic.reciprocal.table->checksum(), checksum);
  EXPECT_EQ(model.arithmetic, measured);
}

}  // namespace
}  // namespace vt
