#pragma once
// Wall-clock seconds for the timings reports print; no result depends on them.

#include <chrono>

namespace vt {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace vt
