#pragma once
// A one-line progress bar with elapsed time and ETA on stderr, redrawn at most ten times a second,
// and silent when stderr is not a terminal (logs and CI stay clean).

#include <chrono>
#include <cstdint>
#include <string>

namespace vt {

class ProgressBar {
 public:
  ProgressBar(std::string label, uint64_t total, bool enabled = true);
  ~ProgressBar();  // ends the line if anything was drawn

  void update(uint64_t done);

 private:
  void draw(uint64_t done);

  std::string label_;
  uint64_t total_;
  bool active_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace vt
