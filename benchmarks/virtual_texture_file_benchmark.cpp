// Random page reads from a virtual-texture file: VirtualTextureReader::readPage (one pread plus
// the XXH3 check of the page) against its peer, a bare pread of the same bytes, in the same
// process over the same file and the same page sequence. Prints the cost of verification as a
// ratio. The file is small enough to stay in the OS cache, so this measures CPU cost, not disk.

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "benchmarks/ratio_reporter.h"
#include "build/synthetic_texture.h"
#include "format/virtual_texture_reader.h"

namespace {

std::vector<uint64_t> randomPages(uint64_t count) {
  std::mt19937_64 random(42);
  std::vector<uint64_t> pages(4096);
  for (auto& page : pages) page = random() % count;
  return pages;
}

void readPageVerified(benchmark::State& state, const std::filesystem::path& file) {
  const vt::VirtualTextureReader reader(file);
  const auto pages = randomPages(reader.storedPageCount());
  std::vector<std::byte> texels(reader.description().pageBytes());
  size_t i = 0;
  for (auto _ : state) {
    reader.readPage(vt::fromAbsoluteIndex(pages[i++ % pages.size()]), texels);
    benchmark::DoNotOptimize(texels.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * texels.size()));
}

void readPageBarePread(benchmark::State& state, const std::filesystem::path& file) {
  const vt::VirtualTextureReader reader(file);
  const auto pages = randomPages(reader.storedPageCount());
  const uint64_t pageBytes = reader.description().pageBytes();
  const uint64_t dataOffset = reader.header().layout.dataOffset;
  std::vector<std::byte> texels(pageBytes);
  const int fd = ::open(file.c_str(), O_RDONLY);
  size_t i = 0;
  for (auto _ : state) {
    const uint64_t offset = dataOffset + pages[i++ % pages.size()] * pageBytes;
    if (::pread(fd, texels.data(), pageBytes, static_cast<off_t>(offset)) !=
        static_cast<ssize_t>(pageBytes))
      state.SkipWithError("short read");
    benchmark::DoNotOptimize(texels.data());
  }
  ::close(fd);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * pageBytes));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  // P = 128, B = 4, RGBA8, levels 0..4: 341 pages of 73,984 bytes (25 MB).
  const auto file = std::filesystem::temp_directory_path() /
                    ("vt-benchmark-" + std::to_string(::getpid()) + ".vt");
  vt::writeSyntheticTexture(
      file, {{.pageSize = 128, .border = 4, .levelCount = 5, .channels = 4}, std::nullopt});
  benchmark::RegisterBenchmark("readPageVerified", readPageVerified, file);
  benchmark::RegisterBenchmark("readPageBarePread", readPageBarePread, file);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.printRatio("readPageVerified", "readPageBarePread",
                      "readPage (pread + XXH3 check) / bare pread: %.2fx the time per page\n");
  std::filesystem::remove(file);
  benchmark::Shutdown();
}
