#pragma once
// The oracle's parallel loops: TBB, or plain std::threads when built with VT_STD_THREAD_WORKERS
// (CMake option, on for ThreadSanitizer). TBB is not instrumented, so TSan reads its internal
// synchronisation as races and cannot check the tile workers; on std::threads it sees every
// hand-over (thread start, the atomic index, join). Each index writes only its own outputs, so
// the bytes are the same either way and for any thread count.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#ifndef VT_STD_THREAD_WORKERS
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#endif

namespace vt {

// Limits the parallelism of everything in its scope to `threads` (0: every core): TBB's loops
// and Embree's scene build. Nothing to limit on std::threads, where parallelFor takes the count.
class ThreadLimit {
 public:
  explicit ThreadLimit(unsigned threads)
#ifndef VT_STD_THREAD_WORKERS
      : limit_(tbb::global_control::max_allowed_parallelism,
               std::max(1u, threads ? threads : std::thread::hardware_concurrency()))
#endif
  {
    (void)threads;
  }

 private:
#ifndef VT_STD_THREAD_WORKERS
  tbb::global_control limit_;
#endif
};

// Runs body(i) for every i in [0, count). With TBB, on the threads the enclosing ThreadLimit
// allows; on std::threads, on `threads` of them (0: every core), the calling thread included.
// The first exception a body throws is rethrown here once every thread has stopped.
template <class Body>
void parallelFor(size_t count, unsigned threads, const Body& body) {
#ifndef VT_STD_THREAD_WORKERS
  (void)threads;
  tbb::parallel_for(size_t{0}, count, [&](size_t i) { body(i); });
#else
  const size_t workers = std::min<size_t>(
      std::max(1u, threads ? threads : std::thread::hardware_concurrency()), count);
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  const auto work = [&] {
    for (size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard lock(errorMutex);
        if (!error) error = std::current_exception();
        next.store(count);  // the remaining indices are not started
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
#endif
}

}  // namespace vt
