#include "verify/crosscheck_captures.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "common/posix_file.h"
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

// Reads and judges one capture: its difference images into `folder`, its entry into `frames`,
// its counts into `totals` and its verdict into `testCase`. Throws where it cannot be read.
void judgeCapture(const std::filesystem::path& manifest, const CapturesCheckOptions& options,
                  const std::filesystem::path& folder, TextureCache& textures,
                  nlohmann::json& frames, ComparisonTotals& totals, JUnitCase& testCase) {
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
  frames.push_back(frameJson(manifest, capture, judge, c, widths));
  totals.add(c, widths);
  printComparison(name, c.model, c, widths);
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

}  // namespace

CapturesCheck crosscheckCaptures(const CapturesCheckOptions& options) {
  const std::vector<std::filesystem::path> manifests = oracle::findCaptures(options.captures);
  if (manifests.empty())
    throw oracle::Error(options.captures.string() + ": no captures (*.json) in the folder");
  TemporaryFolder staging(options.output, "summary.json");
  const std::filesystem::path& folder = staging.path();

  TextureCache textures;
  std::vector<JUnitCase> cases;
  nlohmann::json frames = nlohmann::json::array();
  CapturesCheck check;
  check.captures = manifests.size();
  ComparisonTotals& totals = check.totals;
  size_t& errors = check.unreadable;
  std::printf("crosscheck of %zu captures in %s\n", manifests.size(),
              options.captures.string().c_str());
  for (const std::filesystem::path& manifest : manifests) {
    const auto start = Clock::now();
    JUnitCase testCase{manifest.stem().string(), 0.0, JUnitCase::Outcome::kPassed, "", "", {}};
    try {
      judgeCapture(manifest, options, folder, textures, frames, totals, testCase);
    } catch (const std::exception& e) {
      const std::string message = unreadableMessage(manifest, e);
      ++errors;
      testCase.outcome = JUnitCase::Outcome::kError;
      testCase.message = message;
      frames.push_back({{"capture", manifest.filename().string()}, {"error", message}});
      std::fflush(stdout);
      std::cerr << "vt crosscheck: " << message << "\n";
    }
    testCase.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    cases.push_back(testCase);
  }

  const bool passed = check.passed();
  nlohmann::json totalsJson = totals.json();
  totalsJson["captures"] = manifests.size();
  totalsJson["unreadable"] = errors;
  const nlohmann::json summary = {{"captures", options.captures.string()},
                                  {"model", options.profile},
                                  {"frames", frames},
                                  {"totals", totalsJson},
                                  {"passed", passed}};
  writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
  writeJUnitReport(folder / "junit.xml", "vt crosscheck " + options.captures.string(), cases);
  std::printf("crosscheck: %s, %zu of %zu captures unreadable: %s\n", totals.line().c_str(), errors,
              manifests.size(), passed ? "passed" : "FAILED");
  std::fflush(stdout);
  staging.commit();
  return check;
}

}  // namespace vt
