#include "common/progress_bar.h"

#include <unistd.h>

#include <cstdio>

namespace vt {

ProgressBar::ProgressBar(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)),
      total_(total == 0 ? 1 : total),
      active_(enabled && ::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressBar::~ProgressBar() {
  if (drawn_) {
    draw(total_);
    std::fputc('\n', stderr);
  }
}

void ProgressBar::update(uint64_t done) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - lastDraw_ < std::chrono::milliseconds(100) && done < total_) return;
  lastDraw_ = now;
  draw(done);
}

void ProgressBar::draw(uint64_t done) {
  const double fraction = static_cast<double>(done) / static_cast<double>(total_);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 30;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < static_cast<int>(fraction * kWidth) ? '#' : '.';
  bar[kWidth] = '\0';
  char eta[32] = "";
  if (fraction > 0.0 && fraction < 1.0)
    std::snprintf(eta, sizeof eta, ", ETA %.0f s", elapsed * (1.0 - fraction) / fraction);
  std::fprintf(stderr, "\r%s [%s] %3.0f%% %.1f s%s   ", label_.c_str(), bar, fraction * 100.0,
               elapsed, eta);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace vt
