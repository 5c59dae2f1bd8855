#pragma once
// Streaming (thesis 3.2.5): reading requested pages from the virtual-texture file into the list of
// streamed pages that the management step applies to the cache.
//
// BudgetStreamer is the deterministic mode of the evaluations (thesis 4.1.1): each frame at most
// `pagesPerFrame` of the frame's requests, in order, or as many as `bytesPerFrame` carries at the
// pages' stored size (compressed pages are smaller: format/texture_description.h), optionally
// arriving `latencyFrames` frames later (a link with latency and bandwidth measured per frame). ThreadedStreamer is the
// interactive mode: a thread pops the most important request, reads it and hands it over; every
// frame's requests replace the previous ones, so requests no longer needed are dropped. Its link
// model makes it a slow network in real time (internet-like streaming, thesis chapter 4).

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "format/virtual_texture_reader.h"
#include "runtime/page_priority.h"

namespace vt {

struct StreamedPage {
  uint64_t page;  // absolute index
  std::vector<std::byte> stored;  // as the file holds it: texels, or blocks (readStoredPage)
};

// The streaming box of the frame loop (thesis figure 3.5), either mode: a frame's requests go in,
// the pages that arrive for the next frame come out.
class PageStreamer {
 public:
  virtual ~PageStreamer() = default;
  virtual std::vector<StreamedPage> exchange(const std::vector<StreamRequest>& requests) = 0;
};

// What a frame of BudgetStreamer may send: a number of pages, or of bytes (when not zero; the
// page count then does not apply). Bytes a frame could not use because the next page did not fit
// carry over to the next frame, as a link that was busy to the end of the frame; bytes left when
// the requests ran out do not (an idle link banks nothing).
struct FrameBudget {
  uint32_t pages = 10;
  uint64_t bytes = 0;
};

class BudgetStreamer final : public PageStreamer {
 public:
  BudgetStreamer(const VirtualTextureReader& reader, uint32_t pagesPerFrame,
                 uint32_t latencyFrames = 0);
  BudgetStreamer(const VirtualTextureReader& reader, FrameBudget budget, uint32_t latencyFrames);

  // Takes this frame's requests (most important first) and returns the pages that arrive now.
  std::vector<StreamedPage> frame(const std::vector<StreamRequest>& requests);
  std::vector<StreamedPage> exchange(const std::vector<StreamRequest>& requests) override {
    return frame(requests);
  }

 private:
  const VirtualTextureReader& reader_;
  FrameBudget budget_;
  uint32_t latencyFrames_;
  uint64_t carried_ = 0;  // bytes carried over from the last frame
  std::deque<std::vector<StreamedPage>> inFlight_;  // front arrives next
};

// A link between the file and the cache: pages cross it one after another, each occupying it for
// (its stored bytes: blocks for the compressed formats, decoded after they arrive) /
// bytesPerSecond, and arrive latencySeconds after they left. Zero bandwidth means unlimited.
struct LinkModel {
  double latencySeconds = 0.0;
  double bytesPerSecond = 0.0;
};

class ThreadedStreamer final : public PageStreamer {
 public:
  explicit ThreadedStreamer(const VirtualTextureReader& reader, LinkModel link = {});
  ~ThreadedStreamer();
  ThreadedStreamer(const ThreadedStreamer&) = delete;
  ThreadedStreamer& operator=(const ThreadedStreamer&) = delete;

  // Replaces the pending requests with this frame's (pages already in flight are not repeated).
  void request(const std::vector<StreamRequest>& requests);
  // The pages that arrived since the last call, in the order they were sent.
  std::vector<StreamedPage> takeStreamed();
  // This frame's requests replace the pending ones; what arrived since the last frame comes back.
  std::vector<StreamedPage> exchange(const std::vector<StreamRequest>& requests) override {
    request(requests);
    return takeStreamed();
  }
  // Waits until no request is pending and every page sent has arrived (tests, shutdown).
  void drain();
  // Pages that could not be read (a corrupt page, say); they are dropped, the thread goes on.
  uint64_t failures() const;

 private:
  void run();

  using Clock = std::chrono::steady_clock;
  struct InTransit {
    Clock::time_point arrival;
    StreamedPage page;
  };

  const VirtualTextureReader& reader_;
  const LinkModel link_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<uint64_t> pending_;
  std::deque<InTransit> inTransit_;  // arrival times rise
  Clock::time_point linkFree_{};     // when the link has sent its last page
  uint64_t reading_ = ~uint64_t{0};
  bool busy_ = false, stop_ = false;
  uint64_t failures_ = 0;
  std::thread thread_;
};

}  // namespace vt
