#include "verify/crosscheck_captures.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "common/shard.h"
#include "render/arithmetic_points.h"
#include "render/precision_model_file.h"
#include "verify/comparison_report.h"
#include "verify/junit_report.h"
#include "verify/oracle_conversions.h"
#include "vt/oracle.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json pixelJson(const oracle::PixelDifference& d, int height) {
  return {{"x", d.x},
          {"y", d.y},
          {"image_row", height - 1 - d.y},
          {"expected_need", d.expectedNeed},
          {"actual_need", d.actualNeed},
          {"expected_color", d.expectedColor},
          {"actual_color", d.actualColor},
          {"widen", oracle::reasonName(d.reason)},
          {"widen_by", d.widenBy},
          {"unit", oracle::widthUnit(d.reason)}};
}

std::string pixelLine(const oracle::PixelDifference& d, int height) {
  // Built by appends: GCC 12 warns falsely on "literal" + std::string.
  const auto four = [](const auto& v) {
    std::string text = "(";
    for (int k = 0; k < 4; ++k) text.append(k ? ", " : "").append(std::to_string(v[k]));
    return text.append(")");
  };
  std::string line = "pixel (";
  line.append(std::to_string(d.x)).append(", ").append(std::to_string(d.y));
  line.append(") [image row ").append(std::to_string(height - 1 - d.y));
  line.append("]: needbuffer ").append(four(d.actualNeed)).append(", oracle ");
  line.append(four(d.expectedNeed)).append("; colour ").append(four(d.actualColor));
  line.append(", oracle ").append(four(d.expectedColor));
  line.append("; needs ").append(oracle::reasonName(d.reason)).append(" widened by ");
  return line.append(std::to_string(d.widenBy)).append(" ").append(oracle::widthUnit(d.reason));
}

// The model that judges one capture, and why that one.
struct JudgingModel {
  std::filesystem::path file;  // a model file; empty: a shipped model
  oracle::Profile profile = oracle::Profile::kExact;
  std::string from;  // "option", "capture", "measured", "fingerprint" or "unverified"
};

// --model NAME or FILE judges every capture. auto: the model file the capture names, else a
// measured model of its renderer ($VT_PRECISION_MODELS), else the shipped model whose
// fingerprint the capturing program reproduced, else gl45: a renderer's name decides nothing.
JudgingModel judgingModel(const std::string& option, const oracle::Capture& capture) {
  if (option != "auto") {
    if (isModelName(option)) return {{}, oracle::parseProfile(option), "option"};
    return {option, oracle::Profile::kExact, "option"};
  }
  if (!capture.model.empty()) return {capture.model, oracle::Profile::kExact, "capture"};
  if (const std::optional<std::filesystem::path> measured = measuredModelFile(capture.renderer))
    return {*measured, oracle::Profile::kExact, "measured"};
  if (!capture.fingerprint.empty())
    return {{}, oracle::parseProfile(capture.fingerprint), "fingerprint"};
  return {{}, oracle::Profile::kGl45, "unverified"};
}

using TextureCache = std::map<std::filesystem::path, std::unique_ptr<oracle::Texture>>;

// Warns where a model file was measured on another renderer than the capture's.
void warnOfAnotherRenderer(const std::filesystem::path& manifest, const JudgingModel& judge,
                           const oracle::Capture& capture) {
  if (judge.file.empty()) return;
  const PrecisionModel model = readModelFile(judge.file);
  if (!model.renderer.empty() && model.renderer != capture.renderer)
    std::cerr << "vt crosscheck: " << manifest.string() << ": warning: precision model '"
              << model.name << "' was measured on " << model.renderer
              << ", the capture was drawn by " << capture.renderer << "\n";
}

// One capture's entry in summary.json: what it is, what judged it and the verdict.
nlohmann::json frameJson(const std::filesystem::path& manifest, const oracle::Capture& capture,
                         const JudgingModel& judge, const oracle::Comparison& c,
                         const SetWidths& widths) {
  nlohmann::json mismatches = nlohmann::json::array();
  for (const oracle::PixelDifference& d : c.mismatches)
    mismatches.push_back(pixelJson(d, capture.scene.viewport.height));
  nlohmann::json frame = {{"capture", manifest.filename().string()},
                          {"renderer", capture.renderer},
                          {"model", c.model},
                          {"model_file", judge.file.empty() ? nlohmann::json(nullptr)
                                                            : nlohmann::json(judge.file.string())},
                          {"model_from", judge.from},
                          {"needbuffer_encoding", oracle::toString(capture.needEncoding)},
                          {"filtering", oracle::toString(capture.filtering)},
                          {"sampling", oracle::toString(capture.sampling)}};
  frame.update(comparisonJson(c, widths));
  frame["unexplained_pixels"] = mismatches;
  return frame;
}

// One capture's part of the report: its entry in summary.json, its counts and its JUnit case.
struct CaptureVerdict {
  nlohmann::json frame;
  ComparisonTotals totals;  // of this capture alone
  JUnitCase testCase;
  bool unreadable = false;
};

// Reads and judges one capture: its difference images into `folder`, its verdict into `verdict`.
// Throws where it cannot be read.
void judgeCapture(const std::filesystem::path& manifest, const CapturesCheckOptions& options,
                  const std::filesystem::path& folder, TextureCache& textures,
                  CaptureVerdict& verdict) {
  const std::string name = manifest.stem().string();
  const oracle::Capture capture = oracle::readCapture(manifest);
  std::unique_ptr<oracle::Texture>& texture = textures[capture.texture];
  if (!texture) texture = std::make_unique<oracle::Texture>(oracle::Texture::open(capture.texture));
  const JudgingModel judge = judgingModel(options.profile, capture);
  const oracle::SetScope scope =
      options.allSets ? oracle::SetScope::kEveryPixel : oracle::SetScope::kDiffering;
  warnOfAnotherRenderer(manifest, judge, capture);
  const oracle::CaptureCheck check =
      judge.file.empty()
          ? oracle::checkCapture(capture, *texture, judge.profile, options.threads, scope)
          : oracle::checkCapture(capture, *texture, judge.file, options.threads, scope);
  const oracle::Comparison& c = check.comparison;
  const SetWidths widths = verdictWidths(check.oracle);
  const oracle::Viewport v = capture.scene.viewport;
  writeComparisonImages(folder, name, v, c);
  verdict.frame = frameJson(manifest, capture, judge, c, widths);
  verdict.totals.add(c, widths);
  printComparison(name, c.model, c, widths);
  JUnitCase& testCase = verdict.testCase;
  testCase.properties = widthProperties(c, widths);
  if (!c.passed()) {
    testCase.outcome = JUnitCase::Outcome::kFailed;
    testCase.message = std::to_string(c.unexplained) + " unexplained pixels under " + c.model +
                       " (" + std::to_string(c.needMismatched) + " in the needbuffer)";
    for (size_t k = 0; k < c.mismatches.size() && k < 20; ++k)
      testCase.details.append(pixelLine(c.mismatches[k], v.height)).append("\n");
  }
}

// A capture that could not be read or judged: named by the capture, unless the reader named it
// (or its data file) already.
std::string unreadableMessage(const std::filesystem::path& manifest, const std::exception& e) {
  std::string message = e.what();
  if (!message.starts_with((manifest.parent_path() / manifest.stem()).string()))
    message = std::string(manifest.string()).append(": ").append(e.what());
  return message;
}

// Judges one capture, timed; a capture that cannot be read or judged is an error case.
CaptureVerdict judgeTimed(const std::filesystem::path& manifest,
                          const CapturesCheckOptions& options, const std::filesystem::path& folder,
                          TextureCache& textures) {
  const auto start = Clock::now();
  CaptureVerdict verdict;
  verdict.testCase = {manifest.stem().string(), 0.0, JUnitCase::Outcome::kPassed, "", "", {}};
  try {
    judgeCapture(manifest, options, folder, textures, verdict);
  } catch (const std::exception& e) {
    const std::string message = unreadableMessage(manifest, e);
    verdict = {{{"capture", manifest.filename().string()}, {"error", message}},
               {},
               {manifest.stem().string(), 0.0, JUnitCase::Outcome::kError, message, "", {}},
               true};
    std::fflush(stdout);
    std::cerr << "vt crosscheck: " << message << "\n";
  }
  verdict.testCase.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return verdict;
}

// summary.json and junit.xml of the verdicts, in the captures' order, and the closing line.
CapturesCheck writeReport(const std::filesystem::path& folder, const std::string& captures,
                          const std::string& profile, const std::vector<CaptureVerdict>& verdicts) {
  CapturesCheck check;
  check.captures = verdicts.size();
  nlohmann::json frames = nlohmann::json::array();
  std::vector<JUnitCase> cases;
  for (const CaptureVerdict& verdict : verdicts) {
    frames.push_back(verdict.frame);
    cases.push_back(verdict.testCase);
    check.totals.add(verdict.totals);
    check.unreadable += verdict.unreadable;
  }
  const bool passed = check.passed();
  nlohmann::json totalsJson = check.totals.json();
  totalsJson["captures"] = check.captures;
  totalsJson["unreadable"] = check.unreadable;
  const nlohmann::json summary = {{"captures", captures},
                                  {"model", profile},
                                  {"frames", frames},
                                  {"totals", totalsJson},
                                  {"passed", passed}};
  writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
  writeJUnitReport(folder / "junit.xml", "vt crosscheck " + captures, cases);
  std::printf("crosscheck: %s, %zu of %zu captures unreadable: %s\n", check.totals.line().c_str(),
              check.unreadable, check.captures, passed ? "passed" : "FAILED");
  std::fflush(stdout);
  return check;
}

constexpr const char* kCapturesShardCommand = "crosscheck --captures";

nlohmann::json shardInputs(const CapturesCheckOptions& options) {
  return {{"captures", options.captures.string()},
          {"model", options.profile},
          {"all_sets", options.allSets}};
}

nlohmann::json verdictRecord(const std::string& item, const CaptureVerdict& verdict) {
  return {{"item", item},
          {"frame", verdict.frame},
          {"case", junitCaseRecord(verdict.testCase)},
          {"totals", verdict.totals.record()},
          {"unreadable", verdict.unreadable}};
}

CaptureVerdict verdictFromRecord(const nlohmann::json& record) {
  return {record.at("frame"), ComparisonTotals::fromRecord(record.at("totals")),
          junitCaseFromRecord(record.at("case")), record.at("unreadable").get<bool>()};
}

}  // namespace

CapturesCheck crosscheckCaptures(const CapturesCheckOptions& options) {
  const std::vector<std::filesystem::path> manifests = oracle::findCaptures(options.captures);
  if (manifests.empty())
    throw oracle::Error(options.captures.string() + ": no captures (*.json) in the folder");
  TemporaryFolder staging(options.output, "summary.json");
  const std::filesystem::path& folder = staging.path();
  const Shard part = options.shard.value_or(Shard{});
  ShardFile shard{{}, kCapturesShardCommand,  part, shardInputs(options),
                  {}, nlohmann::json::array()};
  std::vector<std::filesystem::path> mine;
  for (size_t k = 0; k < manifests.size(); ++k) {
    shard.items.push_back(manifests[k].filename().string());
    if (part.holdsInTurn(k)) mine.push_back(manifests[k]);
  }
  std::printf("crosscheck of %zu captures in %s%s\n", mine.size(),
              options.captures.string().c_str(),
              options.shard ? (", shard " + part.text()).c_str() : "");

  TextureCache textures;
  std::vector<CaptureVerdict> verdicts;
  for (const std::filesystem::path& manifest : mine) {
    verdicts.push_back(judgeTimed(manifest, options, folder, textures));
    shard.records.push_back(verdictRecord(manifest.filename().string(), verdicts.back()));
  }
  const CapturesCheck check =
      writeReport(folder, options.captures.string(), options.profile, verdicts);
  if (options.shard) writeShardFile(folder, shard);
  staging.commit();
  return check;
}

bool isCapturesShard(const ShardFile& shard) { return shard.command == kCapturesShardCommand; }

CapturesCheck mergeCapturesShards(const std::vector<ShardFile>& shards,
                                  const std::filesystem::path& output) {
  TemporaryFolder staging(output, "summary.json");
  std::vector<CaptureVerdict> verdicts;
  const std::vector<std::string>& items = shards.front().items;
  std::vector<size_t> next(shards.size(), 0);  // each shard's next record
  for (size_t k = 0; k < items.size(); ++k) {
    const ShardFile& shard = shards[k % shards.size()];
    size_t& position = next[k % shards.size()];
    try {
      if (position >= shard.records.size() || shard.records[position].at("item") != items[k])
        throw InputError(shard.file, "holds no record of " + items[k] + ", which shard " +
                                         shard.shard.text() + " judges");
      verdicts.push_back(verdictFromRecord(shard.records[position++]));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(shard.file, "malformed record of " + items[k] + ": " + jsonErrorText(e));
    } catch (const std::invalid_argument& e) {
      throw InputError(shard.file, "malformed record of " + items[k] + ": " + e.what());
    }
    if (!verdicts.back().unreadable) {
      const std::string stem = std::filesystem::path(items[k]).stem().string();
      for (const char* suffix : {"-color-difference.png", "-classes.png"})
        copyShardFile(shard, stem + suffix, "difference image", staging.path());
    }
  }
  for (size_t s = 0; s < shards.size(); ++s)
    if (next[s] != shards[s].records.size())
      throw InputError(shards[s].file, "holds records of captures that are not its own");
  const nlohmann::json& inputs = shards.front().inputs;
  std::printf("merged %zu shards of the crosscheck of %zu captures\n", shards.size(), items.size());
  const CapturesCheck check = writeReport(staging.path(), inputs.at("captures").get<std::string>(),
                                          inputs.at("model").get<std::string>(), verdicts);
  staging.commit();
  return check;
}

}  // namespace vt
