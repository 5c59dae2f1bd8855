#include "eval/flight_records.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "common/image_file.h"
#include "common/posix_file.h"
#include "render/arithmetic_points.h"

namespace vt {

std::string flightCsvHeader(bool quality, const std::string& prefix) {
  return prefix +
         "frame,covered_pixels,needed_pages,hits,misses,hit_pixels,requested,streamed,evicted,"
         "resident" +
         (quality ? ",rmse,ssim,wssim\n" : "\n");
}

std::string flightCsvRows(const FlightResult& result, bool quality,
                          const std::string& prefixValue) {
  std::ostringstream csv;
  for (size_t f = 0; f < result.frames.size(); ++f) {
    const FrameStatistics& s = result.frames[f].statistics;
    csv << prefixValue << f << ',' << s.coveredPixels << ',' << s.neededPages << ',' << s.hits
        << ',' << s.misses << ',' << s.hitPixels << ',' << s.requested << ',' << s.streamed << ','
        << s.evicted << ',' << s.resident;
    if (quality) {
      const FrameQuality q = result.frames[f].quality.value_or(FrameQuality{});
      csv << ',' << q.rmse << ',' << q.ssim << ',' << q.wssim;
    }
    csv << '\n';
  }
  return csv.str();
}

nlohmann::json flightTotals(const FlightResult& result) {
  nlohmann::json totals = {{"hits", result.totals.hits},
                           {"misses", result.totals.misses},
                           {"streamed", result.totals.streamed},
                           {"evicted", result.totals.evicted}};
  // Over the frames whose quality was measured.
  double rmseSum = 0.0, ssimSum = 0.0, wssimSum = 0.0, ssimMin = 1.0;
  uint64_t measured = 0;
  for (const FlightFrame& frame : result.frames) {
    if (!frame.quality) continue;
    const FrameQuality& q = *frame.quality;
    rmseSum += q.rmse, ssimSum += q.ssim, wssimSum += q.wssim;
    ssimMin = std::min(ssimMin, q.ssim);
    ++measured;
  }
  if (measured == 0) return totals;
  const auto frames = static_cast<double>(measured);
  totals["mean_rmse"] = rmseSum / frames;
  totals["mean_ssim"] = ssimSum / frames;
  totals["min_ssim"] = ssimMin;
  totals["mean_wssim"] = wssimSum / frames;
  return totals;
}

void writeFlightRecords(const std::filesystem::path& folder, const FlightResult& result,
                        bool quality) {
  writeFileAtomically(folder / "frames.csv",
                      flightCsvHeader(quality) + flightCsvRows(result, quality));
}

std::string frameImageName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame%04d.png", frame);
  return name;
}

void writeColorImage(const std::filesystem::path& file, Viewport viewport,
                     std::span<const uint8_t> rgba) {
  const auto width = static_cast<size_t>(viewport.width),
             height = static_cast<size_t>(viewport.height);
  std::vector<uint8_t> rows(rgba.size());
  for (size_t y = 0; y < height; ++y)
    std::copy_n(rgba.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * width * 4), width * 4,
                rows.begin() + static_cast<std::ptrdiff_t>(y * width * 4));
  writeImage8(file, static_cast<uint32_t>(width), static_cast<uint32_t>(height), 4,
              std::as_bytes(std::span(rows)));
}

nlohmann::json flightTimesJson(const FlightTimes& times) {
  return {{"draw", times.draw},           {"analysis", times.analysis},
          {"streaming", times.streaming}, {"reference", times.reference},
          {"metrics", times.metrics},     {"other", times.other}};
}

void writeFlightSummary(const std::filesystem::path& folder,
                        const FlightConfiguration& configuration,
                        const FlightSummaryContext& context, const FlightResult& result) {
  nlohmann::json summary = configuration.toJson();
  summary.erase("name");
  summary.update({{"texture", context.texture},
                  {"frames", context.frames},
                  {"streaming", context.streaming},
                  {"link_latency_seconds", context.linkLatencySeconds},
                  {"link_megabytes_per_second", context.linkMegabytesPerSecond},
                  {"backend", context.backend},
                  {"profile", arithmeticLabel(context.arithmetic)}});
  summary.update(flightTotals(result));
  writeFileAtomically(folder / "summary.json", summary.dump(2) + "\n");
  writeFileAtomically(folder / "timing.json",
                      nlohmann::json{{"seconds", result.seconds},
                                     {"frames", context.frames},
                                     {"quality_seconds", result.qualitySeconds},
                                     {"times", flightTimesJson(result.times)}}
                              .dump(2) +
                          "\n");
}

}  // namespace vt
