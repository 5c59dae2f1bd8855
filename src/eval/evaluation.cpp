#include "eval/evaluation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "reference/texture_source.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

Evaluation evaluate(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                    const std::vector<FlightConfiguration>& configurations,
                    const EvaluationOptions& options) {
  const auto start = Clock::now();
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned jobs =
      std::clamp(options.jobs ? options.jobs : cores, 1u,
                 static_cast<unsigned>(std::max<size_t>(1, configurations.size())));
  const auto frames = static_cast<uint64_t>(path.frameCount());
  const uint64_t total = frames * (1 + configurations.size());
  std::atomic<uint64_t> done{0};
  const auto report = [&] {
    if (options.progress) options.progress(done.load(), total);
  };

  // The reference images, once for every run: the oracle with every page resident, each frame
  // drawn by all cores.
  Evaluation evaluation;
  std::vector<std::vector<uint8_t>> references(frames);
  {
    reference::RenderSettings settings = options.settings;
    settings.threads = options.jobs ? options.jobs : cores;
    const reference::ResidentTexture everything(reader);
    for (uint64_t f = 0; f < frames; ++f) {
      references[f] = referenceImage(everything, mesh, path.at(static_cast<int>(f)), settings);
      ++done;
      report();
    }
  }
  evaluation.referenceSeconds = secondsSince(start);

  // The runs, `jobs` at a time, each drawing with one thread.
  evaluation.runs.resize(configurations.size());
  std::atomic<size_t> next{0};
  std::mutex errorMutex;
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  const auto work = [&] {
    for (size_t r = next++; r < configurations.size() && !failed; r = next++) {
      try {
        FlightOptions flight;
        flight.settings = options.settings;
        flight.settings.threads = 1;
        flight.reference = [&references](int frame) {
          return references[static_cast<size_t>(frame)];
        };
        flight.observe = [&done](const FlightFrameView&) { ++done; };
        evaluation.runs[r] = {configurations[r],
                              fly(reader, mesh, path, configurations[r], flight)};
      } catch (...) {
        const std::lock_guard lock(errorMutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> workers;
  for (unsigned j = 0; j < jobs; ++j) workers.emplace_back(work);
  // The progress is drawn from this thread only.
  while (done.load() < total && !failed) {
    report();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::thread& worker : workers) worker.join();
  if (error) std::rethrow_exception(error);
  report();
  evaluation.wallSeconds = secondsSince(start);
  return evaluation;
}

RangeQuality rangeQuality(const FlightResult& result, int first, int last) {
  RangeQuality quality;
  first = std::max(first, 0);
  last = std::min(last, static_cast<int>(result.frames.size()) - 1);
  if (first > last) return quality;
  for (int f = first; f <= last; ++f) {
    const FrameQuality q = result.frames[static_cast<size_t>(f)].quality.value_or(FrameQuality{});
    quality.meanSsim += q.ssim;
    quality.meanWssim += q.wssim;
    quality.meanRmse += q.rmse;
    quality.minSsim = std::min(quality.minSsim, q.ssim);
  }
  const double count = last - first + 1;
  quality.meanSsim /= count;
  quality.meanWssim /= count;
  quality.meanRmse /= count;
  return quality;
}

}  // namespace vt
