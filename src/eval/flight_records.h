#pragma once
// A flight's results as files: frames.csv (one row per frame: the runtime's statistics and, when
// measured, RMSE, SSIM and WSSIM), the totals as JSON, frame images. Numbers are written the same
// way for any thread count, so two runs compare byte by byte.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "eval/flight.h"

namespace vt {

// The CSV header and rows; `prefix` (e.g. "configuration,") comes before each and `prefixValue`
// (e.g. "3,") before each row.
std::string flightCsvHeader(bool quality, const std::string& prefix = "");
std::string flightCsvRows(const FlightResult& result, bool quality,
                          const std::string& prefixValue = "");

// hits, misses, streamed, evicted; with quality: mean_rmse, mean_ssim, min_ssim, mean_wssim.
nlohmann::json flightTotals(const FlightResult& result);

// Where the flight's time went (FlightTimes), in seconds: draw, analysis, streaming, reference,
// metrics, other.
nlohmann::json flightTimesJson(const FlightTimes& times);

// folder/frames.csv, through a temporary file renamed at the end.
void writeFlightRecords(const std::filesystem::path& folder, const FlightResult& result,
                        bool quality);

// What a flight flew besides its configuration, for its summary.
struct FlightSummaryContext {
  std::string texture;  // as given
  int frames = 0;
  std::string streaming, backend;  // "budget" or "thread"; "oracle" or "gl"
  double linkLatencySeconds = 0, linkMegabytesPerSecond = 0;  // as given
  Arithmetic arithmetic;
};

// folder/summary.json (the configuration without its name, the context, the totals: the same
// bytes for any thread count) and folder/timing.json (where the flight's time went), each through
// a temporary file renamed at the end.
void writeFlightSummary(const std::filesystem::path& folder,
                        const FlightConfiguration& configuration,
                        const FlightSummaryContext& context, const FlightResult& result);

// A frame's image file name, frameNNNN.png (vt fly --images-every, golden sets).
std::string frameImageName(int frame);

// An RGBA8 frame (rows bottom to top, as rendered) as a PNG (rows top to bottom).
void writeColorImage(const std::filesystem::path& file, Viewport viewport,
                     std::span<const uint8_t> rgba);

}  // namespace vt
