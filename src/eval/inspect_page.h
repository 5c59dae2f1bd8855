#pragma once
// The page of the frame-by-frame debugging viewer of a streaming flythrough: one self-contained
// HTML file (no external resources, so it works from file://) that steps through the frames of a
// run and shows, per frame, its images, statistics, the priority queue of page requests and the
// pages streamed for the next frame (or, comparing configurations, each one's queue and pages).
//
// The run travels as JSON inside <script type="application/json" id="inspect-data">, every '<'
// written as \u003c so no string of the data ("</script>", "<!--") can end the element; images
// are PNG data: URIs. Page indices are JSON numbers: exact in JavaScript up to 2^53.
//
// For tests the page keeps its state on <body data-frame="i" data-frames="n"> (i counts frames of
// the run from 0, not InspectFrame::frame) and window.vtSelfTest() (run on load by the URL
// fragment #selftest) steps through every frame with real keydown events and writes
// "selftest ok frames=n" or "selftest failed: <reason>" into the element #selftest.
// The fragment #frame=i opens frame i.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace vt {

// RGBA8, rows from top to bottom; shown scaled to its cell with pixelated filtering.
struct InspectImage {
  std::string name;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
};

// One factor of a request's priority (e.g. pixelsum 812, noisevalue 0.3): a column of the queue.
struct InspectTerm {
  std::string name;
  double value = 0;
};

// One entry of the priority queue.
struct InspectRequest {
  uint64_t page = 0;  // absolute page index
  uint32_t level = 0, x = 0, y = 0;
  double priority = 0;
  std::vector<InspectTerm> terms;
  bool streamed = false;  // chosen to be streamed this frame
};

// One configuration's priority queue and what it streamed; a page comparing two
// configurations shows one of each, side by side, under their labels.
struct InspectQueue {
  std::string label;                  // empty for a page of one configuration
  std::vector<InspectRequest> queue;  // most important first
  std::vector<uint64_t> streamed;     // absolute page indices streamed for the next frame
};

struct InspectFrame {
  int frame = 0;  // the flythrough's own frame number, shown next to the index
  std::vector<std::pair<std::string, std::string>> statistics;
  std::vector<InspectImage> images;
  std::vector<InspectQueue> queues;
};

struct InspectRun {
  std::string title;
  std::vector<std::pair<std::string, std::string>> settings;
  std::vector<InspectFrame> frames;
};

// Writes the page as `file` through a temporary file renamed at the end. Throws InputError naming
// `file` for a run without frames or an image whose size disagrees with its pixels; the same
// input always gives the same bytes.
void writeInspectPage(const std::filesystem::path& file, const InspectRun& run);

// Standard base64 (RFC 4648 section 4) with '=' padding.
std::string encodeBase64(std::span<const uint8_t> bytes);

// The image as an 8-bit RGBA PNG, alpha stored as given (not premultiplied); deterministic.
// Throws std::invalid_argument for a non-positive size or rgba.size() != width * height * 4.
std::vector<uint8_t> encodePng(const InspectImage& image);

}  // namespace vt
