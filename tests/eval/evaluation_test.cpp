// Flights and evaluations (thesis 4.1): a configuration that has every page resident draws the
// reference image itself; budgets hold; results do not depend on how many runs go at once; the
// summary and plots name every configuration.

#include "eval/evaluation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "backends/backend.h"
#include "build/synthetic_texture.h"
#include "common/error.h"
#include "eval/evaluation_report.h"
#include "eval/flight_records.h"
#include "eval/level_comparison.h"
#include "scene/box_room.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

struct EvaluationFixture {
  test::ScratchDirectory dir;
  std::filesystem::path texture = dir / "t.vt";
  TextureDescription description{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4};
  EvaluationFixture() { writeSyntheticTexture(texture, {description, std::nullopt}); }
  // The same texture as BC1, beside it.
  std::filesystem::path writeBc1() const {
    TextureDescription bc1 = description;
    bc1.format = PixelFormat::kBc1;
    writeSyntheticTexture(dir / "bc1.vt", {bc1, std::nullopt});
    return dir / "bc1.vt";
  }
};

EvaluationOptions smallScreen(const VirtualTextureReader& reader, unsigned jobs) {
  EvaluationOptions options;
  options.settings.viewport = {96, 64};
  options.settings.need8 = reader.description().finestLevel() <= 12;
  options.jobs = jobs;
  return options;
}

// The reference image samples each page where it lies in the texture; a flight samples the cache
// texture, whose frame coordinates round differently in float, so even with every page resident a
// few texels differ by one step: that floor stays below RMSE 0.05 and 1 - SSIM 1e-4.
TEST(Evaluation, EveryPageResidentDrawsTheReferenceImageAndNoBudgetStreamsNothing) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  FlightConfiguration everything;
  everything.name = "every page";
  everything.cacheFrames = 37;  // 1369 frames hold all 1365 pages of 6 levels
  everything.initialLevels = 6;
  FlightConfiguration none;
  none.budget = 0;
  FlightConfiguration some;
  some.budget = 3;
  const Evaluation evaluation =
      evaluate(reader, boxRoom(), boxRoomPath(), {everything, none, some}, smallScreen(reader, 2));
  ASSERT_EQ(evaluation.runs.size(), 3u);
  for (const FlightFrame& frame : evaluation.runs[0].result.frames) {
    ASSERT_TRUE(frame.quality);
    EXPECT_LT(frame.quality->rmse, 0.05);
    EXPECT_GT(frame.quality->ssim, 1.0 - 1e-4);
    EXPECT_GT(frame.quality->wssim, 1.0 - 1e-4);
    EXPECT_EQ(frame.statistics.misses, 0u);
  }
  EXPECT_EQ(evaluation.runs[1].result.totals.streamed, 0u);
  EXPECT_LT(flightTotals(evaluation.runs[1].result)["mean_ssim"].get<double>(), 0.999);
  for (const FlightFrame& frame : evaluation.runs[2].result.frames)
    EXPECT_LE(frame.statistics.streamed, 3u);
  // Streaming 3 pages a frame does better than none over the turn.
  EXPECT_GT(flightTotals(evaluation.runs[2].result)["mean_ssim"].get<double>(),
            flightTotals(evaluation.runs[1].result)["mean_ssim"].get<double>());
}

// A compressed texture judged against the uncompressed one: with every page resident a run's
// error is the encoding's alone, which the evaluation also reports apart, frame by frame; a
// reference of other pages is refused naming it.
TEST(Evaluation, AReferenceTextureJudgesTheEncodingApartFromTheStreaming) {
  EvaluationFixture f;
  const VirtualTextureReader uncompressed(f.texture), compressed(f.writeBc1());
  FlightConfiguration everything;
  everything.cacheFrames = 37;
  everything.initialLevels = 6;
  EvaluationOptions options = smallScreen(compressed, 2);
  const Evaluation own = evaluate(compressed, boxRoom(), boxRoomPath(), {everything}, options);
  EXPECT_TRUE(own.encoding.empty());
  options.reference = &uncompressed;
  const Evaluation judged = evaluate(compressed, boxRoom(), boxRoomPath(), {everything}, options);
  const std::vector<FlightFrame>& frames = judged.runs[0].result.frames;
  ASSERT_EQ(judged.encoding.size(), frames.size());
  double encodingSsim = 0.0;
  for (size_t i = 0; i < frames.size(); ++i) {
    ASSERT_TRUE(frames[i].quality);
    // Every page resident: the run differs from the flown texture's own reference by the cache's
    // rounding only (below 1e-4, as above), so its error against the uncompressed one is the
    // encoding's.
    EXPECT_NEAR(frames[i].quality->ssim, judged.encoding[i].ssim, 1e-4) << i;
    EXPECT_GT(own.runs[0].result.frames[i].quality->ssim, 1.0 - 1e-4) << i;
    encodingSsim += judged.encoding[i].ssim / static_cast<double>(frames.size());
  }
  EXPECT_LT(encodingSsim, 0.999);  // BC1 loses detail
  EXPECT_GT(encodingSsim, 0.5);

  writeSyntheticTexture(f.dir / "other.vt",
                        {{.pageSize = 16, .border = 2, .levelCount = 6, .channels = 4}, 0.45});
  const VirtualTextureReader other(f.dir / "other.vt");
  EXPECT_THAT([&] { requireSamePages(compressed, other); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("other.vt")));
  EXPECT_NO_THROW(requireSamePages(compressed, uncompressed));
}

// The encoding's error level by level: none against itself; BC1 against the same pages
// uncompressed loses more where the pages hold finer detail, every level compared page by page.
TEST(Evaluation, LevelsCompareAsTheEncodingChangesThem) {
  EvaluationFixture f;
  const VirtualTextureReader uncompressed(f.texture), compressed(f.writeBc1());
  for (const LevelComparison& l : compareLevels(uncompressed, uncompressed)) {
    EXPECT_EQ(l.pages, uint64_t{1} << (2 * l.level));
    EXPECT_EQ(l.meanSsim, 1.0);
    EXPECT_EQ(l.rmse, 0.0);
    EXPECT_TRUE(std::isinf(l.psnrDb));
  }
  const std::vector<LevelComparison> levels = compareLevels(compressed, uncompressed);
  ASSERT_EQ(levels.size(), 6u);
  for (const LevelComparison& l : levels) {
    EXPECT_EQ(l.pages, uint64_t{1} << (2 * l.level));
    EXPECT_LT(l.meanSsim, 1.0) << l.level;
    EXPECT_GT(l.meanSsim, 0.3) << l.level;
    EXPECT_GT(l.rmse, 0.0) << l.level;
    EXPECT_NEAR(l.psnrDb, 20 * std::log10(255.0 / l.rmse), 1e-9) << l.level;
  }
  const nlohmann::json json = levelComparisonJson(uncompressed, levels);
  EXPECT_EQ(json["levels"].size(), 6u);
  EXPECT_EQ(json["levels"][2]["pages"], 16u);
}

// Trilinear filtering reads the needed page's parent too. With every page the first frame names
// preloaded, and their parents, the first frame is the reference (up to the cache's rounding, as
// above); without the parents it is not. In a cache too small for the turn, keeping the parents
// in use resident wins over the whole flight.
TEST(Evaluation, TrilinearParentsCompleteTheFirstFrameAndHelpASmallCache) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  FlightConfiguration plain;
  plain.preloadVisible = true;
  plain.initialLevels = 1;
  plain.budget = 4;
  FlightConfiguration parents = plain;
  parents.trilinearParents = true;
  FlightConfiguration smallPlain = plain, smallParents = parents;
  smallPlain.cacheFrames = smallParents.cacheFrames = 6;
  const Evaluation e = evaluate(reader, boxRoom(), boxRoomPath(),
                                {plain, parents, smallPlain, smallParents}, smallScreen(reader, 2));
  const FlightFrame& plainFirst = e.runs[0].result.frames.front();
  const FlightFrame& parentsFirst = e.runs[1].result.frames.front();
  EXPECT_EQ(plainFirst.statistics.misses, 0u);
  EXPECT_EQ(parentsFirst.statistics.misses, 0u);
  EXPECT_LT(parentsFirst.quality->rmse, 0.05);
  EXPECT_GT(parentsFirst.quality->ssim, 1.0 - 1e-4);
  EXPECT_GT(plainFirst.quality->rmse, 10 * parentsFirst.quality->rmse);
  const auto meanSsim = [&](size_t run) {
    return flightTotals(e.runs[run].result)["mean_ssim"].get<double>();
  };
  std::printf(
      "first frame RMSE %.4f / %.4f; 6 x 6 frames: mean SSIM %.5f / %.5f (plain / "
      "parents)\n",
      plainFirst.quality->rmse, parentsFirst.quality->rmse, meanSsim(2), meanSsim(3));
  EXPECT_GT(meanSsim(3), meanSsim(2));
}

TEST(Evaluation, PerFrameResultsAreTheSameForOneJobOrSeveral) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  std::vector<FlightConfiguration> configurations(3);
  configurations[0].heuristic = Heuristic::parse("pixelsum");
  configurations[1].heuristic = Heuristic::parse("hotspot*noisevalue");
  configurations[1].lookAhead = LookAhead::kStopFix;
  configurations[2].heuristic = Heuristic::parse("random");
  configurations[2].ancestors = AncestorStrategy::kExtern;
  for (FlightConfiguration& c : configurations) c.budget = 2;
  const auto csv = [&](unsigned jobs) {
    std::string text;
    const Evaluation e =
        evaluate(reader, boxRoom(), boxRoomPath(), configurations, smallScreen(reader, jobs));
    for (const EvaluationRun& run : e.runs) text += flightCsvRows(run.result, true);
    return text;
  };
  const std::string one = csv(1);
  EXPECT_EQ(one, csv(3));
  EXPECT_EQ(std::count(one.begin(), one.end(), '\n'), 3 * boxRoomPath().frameCount());
}

// An evaluation draws each view once and shades it again under every configuration's cache state;
// each run's frames are those of a flight that draws every frame itself, byte for byte: the
// statistics, RMSE, SSIM and WSSIM, for every kind of needbuffer a configuration reads (depth,
// a LookAhead camera, a reduced needbuffer, the previous frame's under asynchronous readback).
TEST(Evaluation, RunsEqualFlightsThatDrawEveryFrameThemselves) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  std::vector<FlightConfiguration> configurations(6);
  configurations[0].heuristic = Heuristic::parse("pixelsum");
  configurations[0].preloadVisible = true;
  configurations[0].trilinearParents = true;
  configurations[1].heuristic = Heuristic::parse("hotspot*noisevalue");
  configurations[1].lookAhead = LookAhead::kStopFix;
  configurations[2].heuristic = Heuristic::parse("distance");
  configurations[2].ancestors = AncestorStrategy::kExtern;
  configurations[3].heuristic = Heuristic::parse("weightedpixel");
  configurations[3].asyncReadback = true;
  configurations[4].heuristic = Heuristic::parse("pixelsum*mipgap");
  configurations[4].needScaleLog2 = 1;
  configurations[4].lookAhead = LookAhead::kPlain;
  configurations[5].heuristic = Heuristic::parse("random");
  configurations[5].seed = 2;
  configurations[5].cacheFrames = 5;  // evictions
  for (FlightConfiguration& c : configurations) c.budget = 2;
  const EvaluationOptions options = smallScreen(reader, 2);
  const Evaluation e = evaluate(reader, boxRoom(), boxRoomPath(), configurations, options);
  const std::unique_ptr<const ResidentRenderer> everything = makeResidentRenderer(reader);
  for (size_t r = 0; r < configurations.size(); ++r) {
    FlightOptions flight;
    flight.settings = options.settings;
    flight.reference = [&](int frame) {
      return referenceImage(*everything, boxRoom(), boxRoomPath().at(frame), options.settings);
    };
    const FlightResult alone = fly(reader, boxRoom(), boxRoomPath(), configurations[r], flight);
    EXPECT_EQ(flightCsvRows(e.runs[r].result, true), flightCsvRows(alone, true)) << "run " << r;
  }
  EXPECT_GT(e.runs[5].result.totals.evicted, 0u);
}

// Random with another seed is another draw: its streamed pages differ; the same seed repeats.
TEST(Evaluation, RandomRunsWithDifferentSeedsDrawDifferentPages) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  std::vector<FlightConfiguration> configurations(3);
  for (FlightConfiguration& c : configurations) {
    c.heuristic = Heuristic::parse("random");
    c.budget = 2;
  }
  configurations[1].seed = configurations[2].seed = 1;
  const Evaluation e =
      evaluate(reader, boxRoom(), boxRoomPath(), configurations, smallScreen(reader, 2));
  const auto csv = [&](size_t run) { return flightCsvRows(e.runs[run].result, true); };
  EXPECT_NE(csv(0), csv(1));
  EXPECT_EQ(csv(1), csv(2));
}

TEST(Evaluation, WritesTheSummaryTablePerMotionMeansAndPlots) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  const CameraPath base = boxRoomPath();
  std::vector<Keyframe> keys = base.keyframes();
  const CameraPath path(
      keys, {{"slow turn", "slow rotation", 0, 20}, {"fast turn", "fast rotation", 30, 32}});
  FlightConfiguration a, b;
  a.name = "PixelSum | 2";  // a '|' must not break the Markdown table
  a.budget = 2;
  b.heuristic = Heuristic::parse("weightedpixel");
  b.budget = 4;
  const EvaluationOptions options = smallScreen(reader, 2);
  const Evaluation evaluation = evaluate(reader, boxRoom(), path, {a, b}, options);
  const EvaluationFigure turns{"turns.png", "Turns", "wssim", {a.label(), b.label()}};
  writeEvaluation(f.dir / "out", {"box room", "box room", "t.vt", 2, {turns}, ""}, path,
                  options.settings, evaluation);
  std::ifstream in(f.dir / "out" / "summary.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THAT(md, HasSubstr("| PixelSum / 2 | "));
  EXPECT_THAT(md, HasSubstr("| weightedpixel 4/frame | "));
  EXPECT_THAT(md, HasSubstr("| fast turn (fast rotation) | 30-32 |"));
  const nlohmann::json summary =
      nlohmann::json::parse(std::ifstream(f.dir / "out" / "summary.json"));
  const RangeQuality slow = rangeQuality(evaluation.runs[1].result, 0, 20);
  EXPECT_EQ(summary["runs"][1]["motions"][0]["mean_ssim"].get<double>(), slow.meanSsim);
  EXPECT_EQ(summary["runs"][0]["streamed"].get<uint64_t>(),
            evaluation.runs[0].result.totals.streamed);
  for (const char* file : {"frames.csv", "ssim.svg", "ssim.png", "wssim.svg", "wssim.png",
                           "rmse.svg", "rmse.png", "turns.svg", "turns.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(f.dir / "out" / file)) << file;
  ASSERT_EQ(summary["figures"].size(), 4u);
  EXPECT_EQ(summary["figures"][3]["stem"], "turns");
  EXPECT_EQ(summary["figures"][3]["measure"], "wssim");
  std::ifstream frames(f.dir / "out" / "frames.csv");
  std::string header;
  std::getline(frames, header);
  EXPECT_EQ(header,
            "configuration,frame,covered_pixels,needed_pages,hits,misses,hit_pixels,requested,"
            "streamed,evicted,resident,rmse,ssim,wssim");
}

// The plots need python3 with matplotlib: without them the evaluation fails with one line naming
// the problem and leaves no output folder ($VT_PYTHON stands in for a broken installation).
TEST(Evaluation, PlotsThatCannotBeDrawnFailTheEvaluationAndLeaveNoFolder) {
  EvaluationFixture f;
  const VirtualTextureReader reader(f.texture);
  FlightConfiguration a;
  a.budget = 2;
  const EvaluationOptions options = smallScreen(reader, 1);
  const CameraPath path = boxRoomPath();
  const Evaluation evaluation = evaluate(reader, boxRoom(), path, {a}, options);
  const std::filesystem::path fake = f.dir / "python-without-matplotlib";
  std::ofstream(fake) << "#!/bin/sh\ncat > /dev/null\necho 'traceback line' >&2\n"
                         "echo 'matplotlib or numpy missing for fake' >&2\nexit 3\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const auto attempt = [&](const std::filesystem::path& python) {
    ::setenv("VT_PYTHON", python.c_str(), 1);
    std::string message;
    try {
      writeEvaluation(f.dir / "out", {"box room", "box room", "t.vt", 1, {}, ""}, path,
                      options.settings, evaluation);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    ::unsetenv("VT_PYTHON");
    EXPECT_FALSE(std::filesystem::exists(f.dir / "out"));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  };
  EXPECT_THAT(attempt(fake), HasSubstr("matplotlib or numpy missing for fake"));
  EXPECT_THAT(attempt(f.dir / "no-such-python"), HasSubstr("cannot run"));
}

TEST(FlightConfiguration, ReadsTheOptionNamesAndRejectsUnknownKeysAndBadValues) {
  const FlightConfiguration c = FlightConfiguration::fromJson(
      nlohmann::json::parse(R"({"heuristic": "hotspot*noisevalue", "lookahead": "stopfix",
        "budget": 5, "ancestors": "extern", "noise_skipping": true, "locked_levels": 4,
        "need_scale": 4, "readback": "async", "trilinear_parents": true, "seed": 3})"),
      {});
  EXPECT_EQ(c.label(),
            "hotspot*noisevalue 5/frame lookahead=stopfix extern skipping locked=4 need=1/4 async "
            "parents seed=3");
  EXPECT_TRUE(c.trilinearParents);
  const FlightConfiguration back = FlightConfiguration::fromJson(c.toJson(), {});
  EXPECT_EQ(back.toJson(), c.toJson());
  const auto error = [](const char* text) {
    try {
      FlightConfiguration::fromJson(nlohmann::json::parse(text), {});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error(R"({"budgett": 5})"), HasSubstr("unknown configuration key 'budgett'"));
  EXPECT_THAT(error(R"({"budget": -1})"), HasSubstr("'budget' must be a whole number"));
  EXPECT_THAT(error(R"({"heuristic": "pixelsum*luck"})"), HasSubstr("'luck' is not one of"));
  EXPECT_THAT(error(R"({"need_scale": 3})"), HasSubstr("need"));
  EXPECT_THAT(error(R"({"lookahead": "far"})"), HasSubstr("lookahead 'far'"));
  EXPECT_THAT(error(R"([1])"), HasSubstr("must be a JSON object"));
  EXPECT_THAT(error(R"({"seed": 1.5})"), HasSubstr("'seed' must be a whole number"));
  EXPECT_THAT(error(R"({"trilinear_parents": "yes"})"),
              HasSubstr("'trilinear_parents' must be true or false"));
  // Prefetching the LookAhead camera's pages: written only where set, and only with a camera.
  EXPECT_FALSE(c.toJson().contains("lookahead_pages"));
  const FlightConfiguration prefetch = FlightConfiguration::fromJson(
      nlohmann::json::parse(R"({"lookahead": "stopfix", "lookahead_pages": "prefetch"})"), {});
  EXPECT_TRUE(prefetch.lookAheadPrefetch);
  EXPECT_EQ(prefetch.label(), "pixelsum 10/frame lookahead=stopfix prefetch");
  EXPECT_EQ(FlightConfiguration::fromJson(prefetch.toJson(), {}).toJson(), prefetch.toJson());
  EXPECT_THAT(error(R"({"lookahead_pages": "prefetch"})"),
              HasSubstr("'lookahead_pages' prefetch prefetches the LookAhead camera's pages: it "
                        "needs a 'lookahead' other than none"));
  EXPECT_THAT(error(R"({"lookahead": "stopfix", "lookahead_pages": "later"})"),
              HasSubstr("'lookahead_pages' must be merged or prefetch"));
  // The LookAhead pixels' weight and the LOD bias's backlog.
  const FlightConfiguration biased = FlightConfiguration::fromJson(
      nlohmann::json::parse(
          R"({"lookahead": "plain", "lookahead_weight": 3, "lod_bias_backlog": 40})"),
      {});
  EXPECT_EQ(biased.label(), "pixelsum 10/frame lookahead=plain lookahead_weight=3 "
                            "lod_bias_backlog=40");
  EXPECT_EQ(FlightConfiguration::fromJson(biased.toJson(), {}).toJson(), biased.toJson());
  EXPECT_FALSE(c.toJson().contains("lookahead_weight"));
  EXPECT_FALSE(c.toJson().contains("lod_bias_backlog"));
  EXPECT_THAT(error(R"({"lookahead_weight": 2})"),
              HasSubstr("'lookahead_weight' weights the LookAhead camera's merged pixels"));
  EXPECT_THAT(error(R"({"lookahead": "plain", "lookahead_weight": 17})"),
              HasSubstr("'lookahead_weight' must be a whole number from 1 to 16"));
}

}  // namespace
}  // namespace vt
