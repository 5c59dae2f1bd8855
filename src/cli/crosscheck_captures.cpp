#include "cli/crosscheck_captures.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/junit_report.h"
#include "common/image_file.h"
#include "common/posix_file.h"
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
          {"actual_color", d.actualColor}};
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
  return line.append(", oracle ").append(four(d.expectedColor));
}

}  // namespace

bool crosscheckCaptures(const CapturesCheckOptions& options) {
  const std::vector<std::filesystem::path> manifests = oracle::findCaptures(options.captures);
  if (manifests.empty())
    throw oracle::Error(options.captures.string() + ": no captures (*.json) in the folder");
  std::filesystem::create_directories(options.output);

  std::map<std::filesystem::path, std::unique_ptr<oracle::Texture>> textures;
  std::vector<JUnitCase> cases;
  nlohmann::json frames = nlohmann::json::array();
  uint64_t totals[5] = {0, 0, 0, 0, 0};  // pixels, identical, flagged, within bound, mismatched
  size_t errors = 0;
  std::printf("crosscheck of %zu captures in %s\n", manifests.size(),
              options.captures.string().c_str());
  for (const std::filesystem::path& manifest : manifests) {
    const std::string name = manifest.stem().string();
    const auto start = Clock::now();
    JUnitCase testCase{name, 0.0, JUnitCase::Outcome::kPassed, "", ""};
    try {
      const oracle::Capture capture = oracle::readCapture(manifest);
      std::unique_ptr<oracle::Texture>& texture = textures[capture.texture];
      if (!texture)
        texture = std::make_unique<oracle::Texture>(oracle::Texture::open(capture.texture));
      const oracle::Profile profile = options.profile == "auto"
                                          ? oracle::profileForRenderer(capture.renderer)
                                          : oracle::parseProfile(options.profile);
      const oracle::CaptureCheck check =
          oracle::checkCapture(capture, *texture, profile, options.threads);
      const oracle::Comparison& c = check.comparison;
      const oracle::Viewport v = capture.scene.viewport;
      writeImage8(options.output / (name + "-color-difference.png"), static_cast<uint32_t>(v.width),
                  static_cast<uint32_t>(v.height), 4,
                  std::as_bytes(std::span(c.colorDifferenceImage)));
      writeImage8(options.output / (name + "-classes.png"), static_cast<uint32_t>(v.width),
                  static_cast<uint32_t>(v.height), 4,
                  std::as_bytes(std::span(c.classificationImage)));
      nlohmann::json mismatches = nlohmann::json::array();
      for (const oracle::PixelDifference& d : c.mismatches)
        mismatches.push_back(pixelJson(d, v.height));
      frames.push_back({{"capture", manifest.filename().string()},
                        {"renderer", capture.renderer},
                        {"profile", oracle::toString(profile)},
                        {"needbuffer_encoding", oracle::toString(capture.needEncoding)},
                        {"filtering", oracle::toString(capture.filtering)},
                        {"sampling", oracle::toString(capture.sampling)},
                        {"pixels", c.pixels},
                        {"identical", c.identical},
                        {"flagged", c.flagged},
                        {"within_bound", c.withinBound},
                        {"mismatched", c.mismatched},
                        {"needbuffer_mismatched", c.needMismatched},
                        {"max_color_difference", c.maxColorDifference},
                        {"mean_color_difference", c.meanColorDifference},
                        {"mismatched_pixels", mismatches}});
      const uint64_t counts[5] = {c.pixels, c.identical, c.flagged, c.withinBound, c.mismatched};
      for (int k = 0; k < 5; ++k) totals[k] += counts[k];
      std::printf(
          "  %-12s %-9s %8llu pixels: %8llu identical, %6llu flagged, %6llu within "
          "bound, %6llu mismatched; colour max %d, mean %.4f\n",
          name.c_str(), oracle::toString(profile).c_str(),
          static_cast<unsigned long long>(c.pixels), static_cast<unsigned long long>(c.identical),
          static_cast<unsigned long long>(c.flagged),
          static_cast<unsigned long long>(c.withinBound),
          static_cast<unsigned long long>(c.mismatched), c.maxColorDifference,
          c.meanColorDifference);
      if (!c.passed()) {
        testCase.outcome = JUnitCase::Outcome::kFailed;
        testCase.message = std::to_string(c.mismatched) + " mismatched pixels (" +
                           std::to_string(c.needMismatched) + " in the needbuffer)";
        for (size_t k = 0; k < c.mismatches.size() && k < 20; ++k)
          testCase.details.append(pixelLine(c.mismatches[k], v.height)).append("\n");
      }
    } catch (const std::exception& e) {
      // Named by the capture, unless the reader named it (or its data file) already.
      std::string message = e.what();
      if (!message.starts_with((manifest.parent_path() / manifest.stem()).string()))
        message = std::string(manifest.string()).append(": ").append(e.what());
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

  const bool passed = totals[4] == 0 && errors == 0;
  nlohmann::json summary = {{"captures", options.captures.string()},
                            {"profile", options.profile},
                            {"frames", frames},
                            {"totals",
                             {{"captures", manifests.size()},
                              {"unreadable", errors},
                              {"pixels", totals[0]},
                              {"identical", totals[1]},
                              {"flagged", totals[2]},
                              {"within_bound", totals[3]},
                              {"mismatched", totals[4]}}},
                            {"passed", passed}};
  writeFileAtomically(options.output / "summary.json", summary.dump(2) + "\n");
  writeJUnitReport(options.output / "junit.xml", "vt crosscheck " + options.captures.string(),
                   cases);
  std::printf(
      "crosscheck: %llu of %llu pixels identical, %llu flagged, %llu within bound, %llu "
      "mismatched, %zu of %zu captures unreadable: %s\n",
      static_cast<unsigned long long>(totals[1]), static_cast<unsigned long long>(totals[0]),
      static_cast<unsigned long long>(totals[2]), static_cast<unsigned long long>(totals[3]),
      static_cast<unsigned long long>(totals[4]), errors, manifests.size(),
      passed ? "passed" : "FAILED");
  std::fflush(stdout);
  return passed;
}

}  // namespace vt
