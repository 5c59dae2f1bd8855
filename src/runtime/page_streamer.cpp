#include "runtime/page_streamer.h"

#include <algorithm>

namespace vt {

BudgetStreamer::BudgetStreamer(const VirtualTextureReader& reader, uint32_t pagesPerFrame,
                               uint32_t latencyFrames)
    : BudgetStreamer(reader, FrameBudget{pagesPerFrame, 0}, latencyFrames) {}

BudgetStreamer::BudgetStreamer(const VirtualTextureReader& reader, FrameBudget budget,
                               uint32_t latencyFrames)
    : reader_(reader), budget_(budget), latencyFrames_(latencyFrames) {}

std::vector<StreamedPage> BudgetStreamer::frame(const std::vector<StreamRequest>& requests) {
  std::vector<StreamedPage> loaded;
  const uint64_t pageBytes = reader_.description().storedPageBytes();
  uint64_t credit = carried_ + budget_.bytes;
  const auto roomForAnother = [&] {
    return budget_.bytes > 0 ? credit >= pageBytes : loaded.size() < budget_.pages;
  };
  size_t k = 0;
  for (; k < requests.size() && roomForAnother(); ++k) {
    // A page still on its way is not requested twice.
    const uint64_t page = requests[k].page;
    const bool inFlight = std::any_of(inFlight_.begin(), inFlight_.end(), [&](const auto& batch) {
      return std::any_of(batch.begin(), batch.end(),
                         [&](const StreamedPage& p) { return p.page == page; });
    });
    if (inFlight) continue;
    loaded.push_back({page, reader_.readStoredPage(fromAbsoluteIndex(page))});
    credit -= budget_.bytes > 0 ? pageBytes : 0;
  }
  // The unused bytes carry over only if requests were left that they could not pay for.
  carried_ = budget_.bytes > 0 && k < requests.size() ? credit : 0;
  inFlight_.push_back(std::move(loaded));
  if (inFlight_.size() <= latencyFrames_) return {};
  std::vector<StreamedPage> arrived = std::move(inFlight_.front());
  inFlight_.pop_front();
  return arrived;
}

ThreadedStreamer::ThreadedStreamer(const VirtualTextureReader& reader, LinkModel link)
    : reader_(reader), link_(link), thread_([this] { run(); }) {}

ThreadedStreamer::~ThreadedStreamer() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ThreadedStreamer::request(const std::vector<StreamRequest>& requests) {
  {
    const std::lock_guard lock(mutex_);
    pending_.clear();
    for (const StreamRequest& r : requests)
      if (r.page != reading_) pending_.push_back(r.page);
  }
  wake_.notify_one();
}

std::vector<StreamedPage> ThreadedStreamer::takeStreamed() {
  const std::lock_guard lock(mutex_);
  std::vector<StreamedPage> pages;
  const Clock::time_point now = Clock::now();
  while (!inTransit_.empty() && inTransit_.front().arrival <= now) {
    pages.push_back(std::move(inTransit_.front().page));
    inTransit_.pop_front();
  }
  return pages;
}

void ThreadedStreamer::drain() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return pending_.empty() && !busy_; });
  if (!inTransit_.empty()) {
    const Clock::time_point last = inTransit_.back().arrival;
    lock.unlock();
    std::this_thread::sleep_until(last);
  }
}

uint64_t ThreadedStreamer::failures() const {
  const std::lock_guard lock(mutex_);
  return failures_;
}

void ThreadedStreamer::run() {
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !pending_.empty(); });
    if (stop_) return;
    const uint64_t page = pending_.front();
    pending_.pop_front();
    reading_ = page;
    busy_ = true;
    lock.unlock();
    std::vector<std::byte> stored;
    bool ok = true;
    try {
      stored = reader_.readStoredPage(fromAbsoluteIndex(page));  // the file, unlocked
    } catch (const std::exception&) {
      ok = false;
    }
    lock.lock();
    if (ok) {
      // The page occupies the link after the previous one, then travels for the latency.
      Clock::time_point sent = std::max(Clock::now(), linkFree_);
      if (link_.bytesPerSecond > 0.0)
        sent += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
            static_cast<double>(reader_.description().storedPageBytes()) /
            link_.bytesPerSecond));
      linkFree_ = sent;
      wake_.wait_until(lock, sent, [this] { return stop_; });
      if (stop_) return;
      const Clock::time_point arrival =
          sent + std::chrono::duration_cast<Clock::duration>(
                     std::chrono::duration<double>(link_.latencySeconds));
      inTransit_.push_back({arrival, {page, std::move(stored)}});
    } else {
      ++failures_;
    }
    reading_ = ~uint64_t{0};
    busy_ = false;
    if (pending_.empty()) idle_.notify_all();
  }
}

}  // namespace vt
