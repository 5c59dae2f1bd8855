// Measured tables (render/measured_table.h) chosen, or refused, by the probes beyond their sweeps.
// llvmpipe's probes are recorded once (about 10 s) and copied for each table; a sweep is then
// replaced by a table one ulp off at every third input, as an implementation whose function unit
// is not IEEE would return it.
//
// The reciprocal, judged by the perspective triangles (calibrate/raster_fit.h):
//   - With llvmpipe's own triangles (drawn with IEEE 1 / q) the table is offered and refused:
//     the triangles choose IEEE, and the model keeps llvmpipe's point.
//   - With the triangles redrawn by the oracle under llvmpipe's arithmetic and that table (what
//     such an implementation draws), the table is chosen and pinned, written beside the model
//     under its checksum, and the model reads back with it.
// sqrt and log2, judged by their 65,536 samples of every exponent (calibrate/shader_math_fit.h):
//   - With llvmpipe's samples (IEEE) the table misses a third of them and sqrt is not pinned.
//   - With the samples answered as that table says, the table pins sqrt and travels beside the
//     model; the residual against the true sqrt still bounds the result sets.
// log2, answered as a table of [1, 2) one ulp high, is pinned by it; 64 ulps high, beyond GLSL's
// bound, it is refused all the same.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "calibrate/probe_texture.h"
#include "calibrate/raster_fit.h"
#include "calibrate/fingerprint.h"
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

bool llvmpipeWithFma() {
  const HeadlessContext context;
  return context.renderer().find("llvmpipe") != std::string::npos &&
         __builtin_cpu_supports("fma");
}

// `vt calibrate --record-probes probes` on llvmpipe, once for the three tables (about 10 s).
void record(const std::filesystem::path& dir, const std::filesystem::path& probes) {
  const test::CommandResult recorded = test::runCommand(
      VT_EXECUTABLE,
      {"calibrate", "--record-probes", probes.string(), "-o", (dir / "here.json").string()}, dir);
  ASSERT_EQ(recorded.exitCode, 0) << recorded.err;
}

// A copy of the recording in a folder of its own, which a table's test changes.
std::filesystem::path copyOf(const std::filesystem::path& recorded,
                             const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::filesystem::copy(recorded, dir / "probes", std::filesystem::copy_options::recursive);
  return dir / "probes";
}

// Each shader probe whose body holds `call` answered again by `answer` (its result's values, from
// the request's inputs); returns how many there were.
size_t answerShaderProbes(
    const std::filesystem::path& probes, const std::string& call,
    const std::function<void(const capture::ProbeRequest&, capture::ProbeResult&)>& answer) {
  const size_t count = capture::readProbeFolder(probes).count;
  size_t answered = 0;
  for (size_t i = 0; i < count; ++i) {
    const capture::ProbeRequest request = capture::readProbeRequest(probes, i);
    if (request.kind != capture::ProbeRequest::Kind::kShader ||
        request.shader.body.find(call) == std::string::npos)
      continue;
    capture::ProbeResult result = capture::readProbeResult(probes, i, request);
    answer(request, result);
    capture::writeProbeResult(probes, i, request, result);
    ++answered;
  }
  return answered;
}

void reciprocalChosenOrRefused(const std::filesystem::path& dir,
                               const std::filesystem::path& probes) {

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
  measured.reciprocal.table = std::make_shared<const MeasuredTable>(TabledFunction::kReciprocal, table);
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
  EXPECT_TRUE(std::filesystem::exists(dir / tableFileName(TabledFunction::kReciprocal, checksum)));
  const PrecisionModel model = readModelFile(dir / "chosen.json");
  ASSERT_TRUE(model.arithmetic.reciprocal.table);
  EXPECT_EQ(model.arithmetic.reciprocal.table->checksum(), checksum);
  EXPECT_EQ(model.arithmetic, measured);
}

void sqrtChosenOrRefused(const std::filesystem::path& dir, const std::filesystem::path& probes) {
  const calibrate::FunctionSweep& sweep = *calibrate::packSweep("sqrt");
  std::vector<uint32_t> table = *capture::readSweepResult(probes, sweep);
  for (size_t i = 2; i < table.size(); i += 3)
    if (std::bit_cast<float>(table[i] + 1) < 2.0f) ++table[i];
  capture::writeSweepResult(probes, sweep, table);

  auto refused = fit(probes, dir / "refused.json");
  EXPECT_FALSE(refused["sqrt"]["pinned"].get<bool>());
  EXPECT_THAT(refused["sqrt"]["finding"].get<std::string>(),
              HasSubstr("the measured table over [1, 4), scaled by powers of 4: "));
  ASSERT_EQ(refused["sqrt"]["members"].size(), 2u);
  EXPECT_GT(refused["sqrt"]["members"][1]["mismatches"].get<uint64_t>(), 15000u);

  // The shader probe of log2 and sqrt answered as the table says.
  const MeasuredTable measured(TabledFunction::kSqrt, table);
  const size_t answered = answerShaderProbes(
      probes, "sqrt(x.x)", [&](const capture::ProbeRequest& request, capture::ProbeResult& result) {
        for (size_t k = 0; k < result.values.size(); ++k)
          result.values[k].y = measured.of(request.shader.inputs[k].x);
      });
  EXPECT_EQ(answered, 1u);
  auto chosen = fit(probes, dir / "chosen.json");
  EXPECT_TRUE(chosen["sqrt"]["pinned"].get<bool>());
  EXPECT_EQ(chosen["sqrt"]["chosen"], "measured");
  EXPECT_THAT(chosen["sqrt"]["finding"].get<std::string>(),
              HasSubstr("the measured table " + measured.checksum()));
  EXPECT_TRUE(std::filesystem::exists(dir / tableFileName(TabledFunction::kSqrt, measured.checksum())));
  const PrecisionModel model = readModelFile(dir / "chosen.json");
  ASSERT_TRUE(model.arithmetic.sqrt.table);
  EXPECT_EQ(model.arithmetic.sqrt.table->checksum(), measured.checksum());
  EXPECT_GT(model.sqrtUlps, 0.5);  // the sets keep the residual against the true sqrt
  // Pinned all the same, so `auto` fingerprints it first: llvmpipe's own sqrt is IEEE, not the
  // table, and the fingerprint says so.
  EXPECT_TRUE(model.pinned());
  const HeadlessContext context;
  const calibrate::Fingerprint print = calibrate::fingerprint(model.arithmetic);
  EXPECT_FALSE(print.reproduced);
  EXPECT_EQ(print.finding, "sqrt differs from the measured table " + measured.checksum());
}

// The sweep and the samples of log2 answered by a table of [1, 2) `ulpsHigh` ulps above the true
// log2 at every third input, except where that would pass 1.
MeasuredTable answerLog2AsTable(const std::filesystem::path& probes, uint32_t ulpsHigh) {
  std::vector<uint32_t> bits(MeasuredTable::kLog2Count);
  for (uint32_t i = 0; i < bits.size(); ++i) {
    const double m = std::bit_cast<float>(MeasuredTable::kLog2First + i);
    bits[i] = std::bit_cast<uint32_t>(static_cast<float>(std::log2(m)));
    // Where it stays within [0, 1], as a table must (measured_table.h).
    if (i % 3 == 1 && std::bit_cast<float>(bits[i] + ulpsHigh) <= 1.0f) bits[i] += ulpsHigh;
  }
  MeasuredTable measured(TabledFunction::kLog2, bits);
  const calibrate::FunctionSweep& sweep = *calibrate::packSweep("log2");
  std::vector<uint32_t> swept(sweep.count);
  for (uint32_t i = 0; i < sweep.count; ++i)
    swept[i] = std::bit_cast<uint32_t>(measured.of(std::bit_cast<float>(sweep.first + i)));
  capture::writeSweepResult(probes, sweep, swept);
  answerShaderProbes(
      probes, "log2(x.x)", [&](const capture::ProbeRequest& request, capture::ProbeResult& result) {
        for (size_t k = 0; k < result.values.size(); ++k)
          result.values[k].x = measured.of(request.shader.inputs[k].x);
      });
  return measured;
}

// A table 64 ulps high: below log2 = 1 that is 64 x 2^-24 = 2^-18, beyond GLSL 4.50's absolute
// error of 2^-21 inside [0.5, 2] (section 4.7.1). The table reproduces every probe all the same;
// pinned by it, log2 is still judged by its residuals, and `vt calibrate` writes no model.
void log2TableBeyondGlslIsRefused(const std::filesystem::path& dir,
                                  const std::filesystem::path& probes) {
  answerLog2AsTable(probes, 64);
  const test::CommandResult refused = test::runCommand(
      VT_EXECUTABLE,
      {"calibrate", "--probes", probes.string(), "-o", (dir / "refused.json").string()}, dir);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_THAT(refused.err, HasSubstr("log2 absolute error inside [0.5, 2]"));
  EXPECT_THAT(refused.err, HasSubstr("the measured table"));
  EXPECT_FALSE(std::filesystem::exists(dir / "refused.json"));
}

// log2, which llvmpipe's polynomial pins, answered instead as a table one ulp high at every third
// input of [1, 2) says, over the whole sweep of [0.5, 2) and the samples of every exponent: no
// closed form reproduces that, and the table pins log2.
void log2BecomesItsTable(const std::filesystem::path& dir, const std::filesystem::path& probes) {
  const MeasuredTable measured = answerLog2AsTable(probes, 1);
  auto chosen = fit(probes, dir / "chosen.json");
  EXPECT_TRUE(chosen["log2"]["pinned"].get<bool>());
  EXPECT_EQ(chosen["log2"]["chosen"], "measured");
  EXPECT_THAT(chosen["log2"]["finding"].get<std::string>(),
              HasSubstr("the measured table " + measured.checksum() +
                        " over [1, 2), plus the exponent in one float addition, bit for bit"));
  EXPECT_THAT(chosen["log2"]["finding"].get<std::string>(), HasSubstr("polynomial_fused "));
  const PrecisionModel model = readModelFile(dir / "chosen.json");
  ASSERT_TRUE(model.arithmetic.log2Table.table);
  EXPECT_EQ(model.arithmetic.log2Table.table->checksum(), measured.checksum());
  EXPECT_TRUE(model.pinned());
  EXPECT_GT(model.log2AbsoluteError, 0.0);  // the sets keep the residual against the true log2
  const HeadlessContext context;
  EXPECT_EQ(calibrate::fingerprint(model.arithmetic).finding,
            "log2 differs from the measured table " + measured.checksum());
}

// The three tables from one recording of llvmpipe's probes, each on a copy of its own.
TEST(MeasuredTableFit, ProbesBeyondEachSweepChooseOrRefuseItsTable) {
  if (!llvmpipeWithFma()) GTEST_SKIP() << "not llvmpipe with FMA";
  test::ScratchDirectory dir;
  ASSERT_NO_FATAL_FAILURE(record(dir.path(), dir / "recorded"));
  {
    SCOPED_TRACE("the reciprocal");
    const std::filesystem::path folder = dir / "reciprocal";
    reciprocalChosenOrRefused(folder, copyOf(dir / "recorded", folder));
  }
  {
    SCOPED_TRACE("sqrt");
    const std::filesystem::path folder = dir / "sqrt";
    sqrtChosenOrRefused(folder, copyOf(dir / "recorded", folder));
  }
  {
    SCOPED_TRACE("log2");
    const std::filesystem::path folder = dir / "log2";
    log2BecomesItsTable(folder, copyOf(dir / "recorded", folder));
  }
  {
    SCOPED_TRACE("log2 beyond GLSL");
    const std::filesystem::path folder = dir / "log2-beyond";
    log2TableBeyondGlslIsRefused(folder, copyOf(dir / "recorded", folder));
  }
}

}  // namespace
}  // namespace vt
