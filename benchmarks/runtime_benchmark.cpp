// The runtime's hot paths against their peers, in one process:
//   - the analysis of a 1920x1080 needbuffer (32-bit) against a plain memcpy of the same buffer
//     (target: at most 2x, the analysis at memory speed);
//   - a page-table update per streamed page (insert plus the eviction it causes) in a 16 x 16
//     frame cache on a texture of levels 0..10, against the thesis's full loop over the table;
//   - streaming throughput: every page of a 25 MB file through the streaming thread (requests in
//     priority order, checksums verified), against a raw sequential read of the same file.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "benchmarks/ratio_reporter.h"
#include "build/synthetic_texture.h"
#include "runtime/needbuffer_analysis.h"
#include "runtime/page_streamer.h"
#include "runtime/page_table.h"

namespace {

// A needbuffer as a frame produces it: runs of equal pages in rows, pages of a few levels.
std::vector<glm::uvec4> frameLikeNeedBuffer() {
  std::vector<glm::uvec4> need(1920 * 1080);
  for (uint32_t y = 0; y < 1080; ++y)
    for (uint32_t x = 0; x < 1920; ++x) {
      const uint32_t level = 6 + (x / 480 + y / 270) % 4;
      need[y * 1920 + x] = glm::uvec4(x / 16 % (1u << level), y / 16 % (1u << level), level, 1);
    }
  return need;
}

void analyzeNeedBuffer(benchmark::State& state) {
  const auto need = frameLikeNeedBuffer();
  for (auto _ : state) {
    const auto analysis = vt::analyzeNeedBuffer(need, {}, 1920, 1080, {});
    benchmark::DoNotOptimize(analysis.coveredPixels);
  }
  state.SetBytesProcessed(
      static_cast<int64_t>(state.iterations() * need.size() * sizeof(glm::uvec4)));
}

void memcpyNeedBuffer(benchmark::State& state) {
  const auto need = frameLikeNeedBuffer();
  std::vector<glm::uvec4> copy(need.size());
  for (auto _ : state) {
    std::memcpy(copy.data(), need.data(), need.size() * sizeof(glm::uvec4));
    benchmark::DoNotOptimize(copy.data());
  }
  state.SetBytesProcessed(
      static_cast<int64_t>(state.iterations() * need.size() * sizeof(glm::uvec4)));
}

// Random pages of levels 4..10 streamed into a full cache (LRU by arrival order).
struct StreamingScenario {
  vt::PageTable table{11};
  std::vector<uint64_t> frames;  // resident page per frame slot
  std::mt19937_64 random{3};
  size_t next = 0;
  StreamingScenario() {
    table.insert(vt::PageId{}, vt::FrameId{0, 0});
    for (uint32_t k = 1; k < 256; ++k) frames.push_back(randomPage());
    for (size_t k = 0; k < frames.size(); ++k) insertIfNew(k);
  }
  uint64_t randomPage() {
    return vt::firstPageOfLevel(4) + random() % (vt::pageCount(10) - vt::firstPageOfLevel(4));
  }
  void insertIfNew(size_t slot) {
    const vt::PageId page = vt::fromAbsoluteIndex(frames[slot]);
    if (!table.resident(page))
      table.insert(page,
                   vt::FrameId{static_cast<uint32_t>(slot % 16), static_cast<uint32_t>(slot / 16)});
  }
  void stream() {
    const size_t slot = next++ % frames.size();
    const vt::PageId old = vt::fromAbsoluteIndex(frames[slot]);
    if (table.resident(old)) table.evict(old);
    frames[slot] = randomPage();
    insertIfNew(slot);
  }
};

void pageTableIncremental(benchmark::State& state) {
  StreamingScenario scenario;
  for (auto _ : state) scenario.stream();
}

void pageTableFullLoop(benchmark::State& state) {
  StreamingScenario scenario;
  for (auto _ : state) {
    scenario.stream();
    scenario.table.recomputeAll();  // what the thesis does after every change
  }
}

// The benchmark's virtual-texture file: P = 128, B = 4, RGBA8, levels 0..4 (341 pages, 25 MB),
// written when a streaming benchmark first runs and removed at exit.
const std::filesystem::path& streamingFile() {
  struct File {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("vt-runtime-bench-" + std::to_string(::getpid()) + ".vt");
    File() {
      vt::writeSyntheticTexture(
          path, {{.pageSize = 128, .border = 4, .levelCount = 5, .channels = 4}, std::nullopt});
    }
    ~File() { std::filesystem::remove(path); }
  };
  static const File file;
  return file.path;
}

void streamingThread(benchmark::State& state) {
  const vt::VirtualTextureReader reader(streamingFile());
  std::vector<vt::StreamRequest> requests;
  for (uint64_t p = 0; p < reader.storedPageCount(); ++p) requests.push_back({p, 1.0});
  for (auto _ : state) {
    vt::ThreadedStreamer streamer(reader);
    streamer.request(requests);
    streamer.drain();
    benchmark::DoNotOptimize(streamer.takeStreamed().size());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * reader.storedPageCount() *
                                               reader.description().pageBytes()));
}

void sequentialRead(benchmark::State& state) {
  const uint64_t bytes = std::filesystem::file_size(streamingFile());
  std::vector<char> buffer(bytes);
  for (auto _ : state) {
    std::ifstream in(streamingFile(), std::ios::binary);
    in.read(buffer.data(), static_cast<std::streamsize>(bytes));
    benchmark::DoNotOptimize(buffer.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
}

BENCHMARK(analyzeNeedBuffer);
BENCHMARK(memcpyNeedBuffer);
BENCHMARK(pageTableIncremental);
BENCHMARK(pageTableFullLoop);
BENCHMARK(streamingThread)->UseRealTime();
BENCHMARK(sequentialRead)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatio(
      "analyzeNeedBuffer", "memcpyNeedBuffer",
      "\nneedbuffer analysis / memcpy of the same 1920x1080 buffer: %.2fx (target <= 2)\n");
  reporter.printRatio(
      "pageTableFullLoop", "pageTableIncremental",
      "page-table update per streamed page: the full loop takes %.0fx the incremental time\n");
  reporter.printRatio("streamingThread", "sequentialRead",
                      "every page through the streaming thread (pread, checksum, hand-over) / a "
                      "sequential read of the file: %.2fx the time\n");
  benchmark::Shutdown();
}
