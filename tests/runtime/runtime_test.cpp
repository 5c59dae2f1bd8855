// The management step against first principles: after any preload and streaming, every
// indirection entry names the frame that holds the page's best resident ancestor, and that frame
// holds exactly that page's texels. Streaming respects its budget, latency and ordering.

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <numeric>
#include <set>

#include "build/synthetic_texture.h"
#include "render/cache_state.h"
#include "runtime/virtual_texture_runtime.h"
#include "test_support.h"

namespace vt {
namespace {

class Runtime : public ::testing::Test {
 protected:
  void SetUp() override {
    writeSyntheticTexture(
        dir_ / "t.vt",
        {{.pageSize = 8, .border = 1, .levelCount = 4, .channels = 3}, std::nullopt});
    reader_ = std::make_unique<VirtualTextureReader>(dir_ / "t.vt");
  }

  // Checks the whole cache state against the page table's resident set, texel by texel.
  void expectConsistent(const VirtualTextureRuntime& runtime) {
    const CacheState& cache = runtime.cacheState();
    const TextureDescription& d = cache.description;
    const uint32_t side = d.storedPageSide();
    for (uint32_t m = 0; m < d.levelCount; ++m)
      for (uint64_t p = 0; p < pagesInLevel(m); ++p) {
        PageId page = fromRelativeIndex(p, m);
        while (!runtime.pageTable().resident(page)) page = parent(page);
        const glm::u16vec4 entry = cache.indirection.entry(fromRelativeIndex(p, m));
        ASSERT_EQ(entry.z, page.level);
        ASSERT_EQ(runtime.pageCache().frameOf(absoluteIndex(page)), (FrameId{entry.x, entry.y}));
        // The frame's first texel row equals the page's.
        const std::vector<std::byte> texels = reader_->readPage(page);
        for (uint32_t x = 0; x < side; ++x) {
          const glm::u8vec4 expected = expandToRgba(texels.data() + x * d.channels, d.channels);
          const uint8_t* got =
              cache.texels.data() +
              (size_t{entry.y} * side * cache.widthTexels + entry.x * side + x) * 4;
          ASSERT_EQ(glm::u8vec4(got[0], got[1], got[2], got[3]), expected);
        }
      }
  }

  test::ScratchDirectory dir_;
  std::unique_ptr<VirtualTextureReader> reader_;
};

TEST_F(Runtime, CacheStateFollowsEveryInsertionAndEviction) {
  RuntimeOptions options;
  options.framesX = 3;
  options.framesY = 2;  // six frames for 85 pages: evictions all the time
  options.lockedLevels = 1;
  VirtualTextureRuntime runtime(*reader_, options);
  expectConsistent(runtime);
  const std::vector<uint64_t> initial = {1, 2, 3, 4};
  runtime.preload(initial);
  expectConsistent(runtime);
  BudgetStreamer streamer(*reader_, 2);
  for (uint64_t step = 0; step < 30; ++step) {
    const std::vector<StreamRequest> requests = {{5 + (step * 7) % 80, 1.0},
                                                 {5 + (step * 13) % 80, 0.5}};
    runtime.apply(streamer.frame(requests));
    expectConsistent(runtime);
    EXPECT_TRUE(runtime.pageCache().contains(0));  // locked
  }
  EXPECT_GT(runtime.pageCache().statistics().evictions, 10u);
}

TEST_F(Runtime, BudgetStreamerLoadsAtMostItsBudgetAfterTheLatency) {
  BudgetStreamer streamer(*reader_, 2, 1);
  const std::vector<StreamRequest> requests = {{7, 3.0}, {8, 2.0}, {9, 1.0}};
  EXPECT_TRUE(streamer.frame(requests).empty());  // one frame of latency
  const auto arrived = streamer.frame(requests);  // 7 and 8 are in flight: 9 is read now
  ASSERT_EQ(arrived.size(), 2u);
  EXPECT_EQ(arrived[0].page, 7u);
  EXPECT_EQ(arrived[1].page, 8u);
  EXPECT_EQ(arrived[0].stored, reader_->readStoredPage(fromAbsoluteIndex(7)));
  const auto next = streamer.frame({});
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].page, 9u);
}

TEST_F(Runtime, ABudgetOfBytesSendsWhatItPaysForAtThePagesStoredSize) {
  // Pages of 10 x 10 texels of 3 bytes: 300 bytes each. 700 bytes a frame send two pages and
  // carry 100 over while requests wait; the third frame has 800 and sends two more, carrying 200.
  const uint64_t pageBytes = reader_->description().storedPageBytes();
  ASSERT_EQ(pageBytes, 300u);
  BudgetStreamer streamer(*reader_, FrameBudget{.pages = 1, .bytes = 700}, 0);
  std::vector<StreamRequest> requests;
  for (uint64_t p = 10; p < 40; ++p) requests.push_back({p, 1.0});
  std::vector<size_t> sent;
  for (int frame = 0; frame < 4; ++frame) {
    const auto arrived = streamer.frame(requests);
    sent.push_back(arrived.size());
    for (const StreamedPage& page : arrived)
      requests.erase(std::find_if(requests.begin(), requests.end(),
                                  [&](const StreamRequest& r) { return r.page == page.page; }));
  }
  // 700, 800, 900 (3 pages, 0 left), 700.
  EXPECT_EQ(sent, (std::vector<size_t>{2, 2, 3, 2}));
  // Bytes left when the requests run out are not banked: a frame with one request sends one,
  // and the next frame has 700 again, not 1100.
  EXPECT_EQ(streamer.frame({{50, 1.0}}).size(), 1u);
  EXPECT_EQ(streamer.frame(requests).size(), 2u);

  // Compressed pages of the same texture cost less: BC1 stores 12 x 12 texels in 72 bytes.
  TextureDescription bc1{.pageSize = 8, .border = 2, .levelCount = 4, .channels = 4};
  bc1.format = PixelFormat::kBc1;
  writeSyntheticTexture(dir_ / "bc1.vt", {bc1, std::nullopt});
  const VirtualTextureReader compressed(dir_ / "bc1.vt");
  ASSERT_EQ(compressed.description().storedPageBytes(), 72u);
  BudgetStreamer blocks(compressed, FrameBudget{.pages = 1, .bytes = 700}, 0);
  EXPECT_EQ(blocks.frame(requests).size(), 9u);  // 648 of 700 bytes
}

TEST_F(Runtime, ThreadedStreamerReadsTheLatestRequests) {
  ThreadedStreamer streamer(*reader_);
  streamer.request({{3, 1.0}, {4, 1.0}, {5, 1.0}});
  streamer.drain();
  std::set<uint64_t> pages;
  for (const StreamedPage& page : streamer.takeStreamed()) {
    pages.insert(page.page);
    EXPECT_EQ(page.stored, reader_->readStoredPage(fromAbsoluteIndex(page.page)));
  }
  EXPECT_EQ(pages, (std::set<uint64_t>{3, 4, 5}));
  EXPECT_TRUE(streamer.takeStreamed().empty());
  EXPECT_EQ(streamer.failures(), 0u);
}

TEST_F(Runtime, ThreadedStreamerTakesRequestsReplacedWhileItReads) {
  // The management thread replaces the requests and takes pages while the streaming thread reads
  // (the case the ThreadSanitizer run of CI watches).
  ThreadedStreamer streamer(*reader_);
  std::set<uint64_t> received;
  for (uint64_t round = 0; round < 200; ++round) {
    streamer.request({{(round * 17) % 85, 1.0}, {(round * 31) % 85, 0.5}, {(round * 7) % 85, 0.2}});
    for (const StreamedPage& page : streamer.takeStreamed()) {
      ASSERT_EQ(page.stored.size(), reader_->description().storedPageBytes());
      received.insert(page.page);
    }
  }
  streamer.drain();
  for (const StreamedPage& page : streamer.takeStreamed()) received.insert(page.page);
  EXPECT_FALSE(received.empty());
  EXPECT_EQ(streamer.failures(), 0u);
}

// A cache far smaller than the stream keeps the root whatever it evicts: every indirection entry
// always names a resident page (an entry without one would send the shader to a garbage level).
TEST_F(Runtime, TheRootNeverLeavesATinyCache) {
  RuntimeOptions options;
  options.framesX = 2;
  options.framesY = 1;
  VirtualTextureRuntime runtime(*reader_, options);
  for (uint64_t round = 0; round < 40; ++round) {
    std::vector<StreamedPage> pages;
    for (uint64_t k = 0; k < 3; ++k) {
      const uint64_t page = 1 + (round * 3 + k) % 84;
      pages.push_back({page, reader_->readPage(fromAbsoluteIndex(page))});
    }
    runtime.apply(std::move(pages));
    ASSERT_TRUE(runtime.pageCache().contains(0)) << "round " << round;
    const IndirectionTable& indirection = runtime.cacheState().indirection;
    for (uint32_t m = 0; m < indirection.levelCount(); ++m)
      for (const glm::u16vec4& entry : indirection.level(m))
        ASSERT_LE(entry.z, 3) << "round " << round;
    expectConsistent(runtime);
  }
}

// The link model gives lower bounds on arrival times, so the properties below hold however slowly
// the machine runs: no page before the latency, and no faster than the bandwidth.
TEST_F(Runtime, ThreadedStreamerLinkDelaysEveryPageByItsLatency) {
  using Clock = std::chrono::steady_clock;
  const double latency = 0.15;
  ThreadedStreamer streamer(*reader_, {.latencySeconds = latency, .bytesPerSecond = 0.0});
  const Clock::time_point start = Clock::now();
  streamer.request({{3, 1.0}, {4, 1.0}, {5, 1.0}});
  std::vector<uint64_t> order;
  while (order.size() < 3) {
    const std::vector<StreamedPage> pages = streamer.takeStreamed();
    if (!pages.empty()) {
      ASSERT_GE(std::chrono::duration<double>(Clock::now() - start).count(), latency);
    }
    for (const StreamedPage& page : pages) order.push_back(page.page);
    ASSERT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 60.0);
  }
  EXPECT_EQ(order, (std::vector<uint64_t>{3, 4, 5}));  // in the order they were sent
}

TEST_F(Runtime, ThreadedStreamerLinkSendsNoFasterThanItsBandwidth) {
  using Clock = std::chrono::steady_clock;
  const double perPage = 0.04;  // seconds on the link per page
  const auto bandwidth = static_cast<double>(reader_->description().pageBytes()) / perPage;
  ThreadedStreamer streamer(*reader_, {.latencySeconds = 0.0, .bytesPerSecond = bandwidth});
  const Clock::time_point start = Clock::now();
  streamer.request({{1, 1.0}, {2, 1.0}, {3, 1.0}, {4, 1.0}, {5, 1.0}});
  streamer.drain();
  EXPECT_GE(std::chrono::duration<double>(Clock::now() - start).count(), 5 * perPage);
  EXPECT_EQ(streamer.takeStreamed().size(), 5u);
}

// A needbuffer of 4 x 4 pixels that all need page (1, 1) of level 2.
std::vector<glm::uvec4> needingOnePage() { return std::vector<glm::uvec4>(16, {1, 1, 2, 1}); }

TEST_F(Runtime, TrilinearParentsRequestsTheParentOfANeededPage) {
  const uint64_t child = absoluteIndex(PageId{1, 1, 2}), up = absoluteIndex(PageId{0, 0, 1});
  for (const bool parents : {false, true}) {
    RuntimeOptions options;
    options.trilinearParents = parents;
    VirtualTextureRuntime runtime(*reader_, options);
    FrameStatistics statistics;
    const std::vector<StreamRequest> requests =
        runtime.analyze(needingOnePage(), {}, 4, 4, false, 0, statistics);
    std::set<uint64_t> requested;
    for (const StreamRequest& r : requests) requested.insert(r.page);
    const std::set<uint64_t> expected =
        parents ? std::set<uint64_t>{child, up} : std::set<uint64_t>{child};
    EXPECT_EQ(requested, expected);
    // The statistics still describe the needbuffer: one page, one miss.
    EXPECT_EQ(statistics.neededPages, 1u);
    EXPECT_EQ(statistics.misses, 1u);
    EXPECT_EQ(statistics.requested, parents ? 2u : 1u);
  }
}

// The LookAhead camera's pages merged with the drawn frame's rank by their pixels among them; as a
// prefetch they come after every request of the drawn frame, whatever their pixels, and a page
// both name is requested once, where the drawn frame puts it.
TEST_F(Runtime, PrefetchedLookAheadPagesComeAfterTheFramesOwn) {
  // The drawn frame: 4 pixels need page (1, 1, 2), 12 need (0, 0, 1). The LookAhead camera's
  // 16 pixels: 14 need (3, 3, 2), 2 need (0, 0, 1).
  std::vector<glm::uvec4> drawn(16, {0, 0, 1, 1}), ahead(16, {3, 3, 2, 1});
  for (int i = 0; i < 4; ++i) drawn[static_cast<size_t>(i)] = {1, 1, 2, 1};
  ahead[0] = ahead[1] = {0, 0, 1, 1};
  const uint64_t mine = absoluteIndex(PageId{1, 1, 2}), shared = absoluteIndex(PageId{0, 0, 1}),
                 predicted = absoluteIndex(PageId{3, 3, 2});
  for (const bool prefetch : {false, true}) {
    SCOPED_TRACE(prefetch ? "prefetch" : "merged");
    RuntimeOptions options;
    options.lookAheadPrefetch = prefetch;
    VirtualTextureRuntime runtime(*reader_, options);
    FrameStatistics statistics;
    const std::vector<StreamRequest> requests = runtime.analyze(
        drawn, {}, 4, 4, false, 0, statistics, {.hotSpot = std::nullopt, .lookAheadNeed = ahead});
    std::vector<uint64_t> order;
    for (const StreamRequest& r : requests) order.push_back(r.page);
    // PixelSum: merged, shared has 12 + 2 pixels, predicted 14, mine 4 (ties: smaller index).
    const std::vector<uint64_t> expected =
        prefetch ? std::vector<uint64_t>{shared, mine, predicted}
                 : std::vector<uint64_t>{std::min(shared, predicted), std::max(shared, predicted),
                                         mine};
    EXPECT_EQ(order, expected);
  }
}

// Weighted, the LookAhead camera's 14 pixels count three times and outrank the drawn frame's page
// of 12 + 2 x 3 = 18 pixels: 42 against 18 (the test above: 14 against 14).
TEST_F(Runtime, WeightedLookAheadPixelsCountMoreThanDrawnOnes) {
  std::vector<glm::uvec4> drawn(16, {0, 0, 1, 1}), ahead(16, {3, 3, 2, 1});
  for (int i = 0; i < 4; ++i) drawn[static_cast<size_t>(i)] = {1, 1, 2, 1};
  ahead[0] = ahead[1] = {0, 0, 1, 1};
  RuntimeOptions options;
  options.lookAheadWeight = 3;
  VirtualTextureRuntime runtime(*reader_, options);
  FrameStatistics statistics;
  const std::vector<StreamRequest> requests = runtime.analyze(
      drawn, {}, 4, 4, false, 0, statistics, {.hotSpot = std::nullopt, .lookAheadNeed = ahead});
  ASSERT_EQ(requests.size(), 3u);
  EXPECT_EQ(requests[0].page, absoluteIndex(PageId{3, 3, 2}));
  EXPECT_EQ(requests[0].priority, 42.0);
  EXPECT_EQ(requests[1].priority, 18.0);
}

// With a backlog above the bias's threshold the missing pages' parents come first, with their
// children's pixels, then the pages themselves; at or below it the requests are as without.
TEST_F(Runtime, ALodBiasRequestsParentsFirstWhileTheBacklogIsLarge) {
  // 16 pixels need the 4 pages of level 3 under (0, 0, 2): 4 pixels each; nothing below level 2
  // is resident, so (0, 0, 2) is missing as well.
  std::vector<glm::uvec4> need(16);
  for (uint32_t i = 0; i < 16; ++i) need[i] = {(i / 4) % 2, (i / 8), 3, 1};
  const uint64_t parent = absoluteIndex(PageId{0, 0, 2});
  for (const uint32_t backlog : {0u, 3u, 4u}) {
    SCOPED_TRACE(backlog);
    RuntimeOptions options;
    options.lodBiasBacklog = backlog;
    VirtualTextureRuntime runtime(*reader_, options);
    FrameStatistics statistics;
    const std::vector<StreamRequest> requests =
        runtime.analyze(need, {}, 4, 4, false, 0, statistics);
    EXPECT_EQ(statistics.misses, 4u);
    const bool biased = backlog == 3;  // 4 missing: above 3, not above 4; 0 is off
    ASSERT_EQ(requests.size(), biased ? 5u : 4u);
    EXPECT_EQ(requests[0].page == parent, biased);
    if (biased) {
      EXPECT_EQ(requests[0].priority, 16.0);
    }
    for (size_t k = biased ? 1 : 0; k < requests.size(); ++k)
      EXPECT_EQ(levelOfAbsoluteIndex(requests[k].page), 3u);
  }
}

TEST_F(Runtime, TrilinearParentsKeepsAParentInUseFromEviction) {
  // Four frames: the root, the needed page, its parent and one more. Pages nobody needs arrive
  // frame after frame; the LRU frame goes to each. The parent, never named by the needbuffer, is
  // the least recently used page unless the analysis touches it.
  const uint64_t child = absoluteIndex(PageId{1, 1, 2}), up = absoluteIndex(PageId{0, 0, 1});
  for (const bool parents : {false, true}) {
    RuntimeOptions options;
    options.framesX = options.framesY = 2;
    options.trilinearParents = parents;
    VirtualTextureRuntime runtime(*reader_, options);
    runtime.preload(std::vector<uint64_t>{up, child});
    for (uint64_t frame = 0; frame < 4; ++frame) {
      FrameStatistics statistics;
      runtime.analyze(needingOnePage(), {}, 4, 4, false, frame, statistics);
      const uint64_t other = absoluteIndex(PageId{static_cast<uint32_t>(frame), 7, 3});
      runtime.apply({StreamedPage{other, reader_->readStoredPage(fromAbsoluteIndex(other))}});
      EXPECT_TRUE(runtime.pageCache().contains(child));
    }
    EXPECT_EQ(runtime.pageCache().contains(up), parents) << "trilinear parents " << parents;
    expectConsistent(runtime);
  }
}

// The cache texture's frames that no page filled are not written: a configuration pays for the
// pages it streams, not for the cache it could fill (`vt eval` holds one cache per
// configuration). A 1000 x 1000-frame cache (400 MB of texels) holding this texture's 85 pages
// keeps almost all of its memory pages untouched, as mincore reports them; a cache zeroed
// element by element would have every one resident. The bound, 5% of the buffer, leaves room for
// transparent huge pages (2 MB where a page is written) and is 20 times below that failure.
TEST_F(Runtime, CacheTextureFramesNoPageFilledCostNoMemory) {
  // Measured: under ThreadSanitizer every page of the buffer is resident after the calloc.
  if (test::kThreadSanitizer) GTEST_SKIP() << "ThreadSanitizer's calloc clears the memory itself";
  RuntimeOptions options;
  options.framesX = options.framesY = 1000;
  VirtualTextureRuntime runtime(*reader_, options);
  std::vector<uint64_t> every(85);
  std::iota(every.begin(), every.end(), uint64_t{0});
  runtime.preload(every);
  expectConsistent(runtime);

  const ZeroedBytes& texels = runtime.cacheState().texels;
  ASSERT_EQ(texels.size(), size_t{10000} * 10000 * 4);
  const auto pageBytes = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<uintptr_t>(texels.data()) / pageBytes * pageBytes;
  const auto end = reinterpret_cast<uintptr_t>(texels.data() + texels.size());
  std::vector<unsigned char> resident((end - begin + pageBytes - 1) / pageBytes);
  // NOLINTNEXTLINE(performance-no-int-to-ptr): mincore takes the page-aligned start
  ASSERT_EQ(mincore(reinterpret_cast<void*>(begin), end - begin, resident.data()), 0);
  const auto residentPages = static_cast<size_t>(
      std::count_if(resident.begin(), resident.end(), [](unsigned char r) { return r & 1; }));
  EXPECT_LT(residentPages, resident.size() / 20) << residentPages << " of " << resident.size();
  // And the untouched frames read as zero (a sample across the whole texture).
  for (size_t i = 0; i < texels.size(); i += 4099 * 4) {
    const uint32_t x = static_cast<uint32_t>(i / 4 % 10000),
                   y = static_cast<uint32_t>(i / 4 / 10000);
    if (y >= 10 || x >= 850) {
      ASSERT_EQ(texels[i], 0) << i;
    }
  }
}

}  // namespace
}  // namespace vt
