#include "runtime/virtual_texture_runtime.h"

#include <algorithm>
#include <unordered_set>

#include "common/error.h"
#include "common/resource_limits.h"

namespace vt {
namespace {

// Adds to every page of level m > 0 in `analysis` its parent, the coarser level that trilinear
// filtering blends in, needed by the same pixels with the same weights. Children are visited in
// page order, so the sums are the same bytes on every run; a parent's index is below its
// children's, so each page passes on its own statistics before its children add theirs.
void addTrilinearParents(NeedBufferAnalysis& analysis) {
  std::vector<uint64_t> children;
  children.reserve(analysis.pages.size());
  for (const auto& [absolute, statistics] : analysis.pages)
    if (levelOfAbsoluteIndex(absolute) > 0) children.push_back(absolute);
  std::sort(children.begin(), children.end());
  for (const uint64_t child : children) {
    const PageStatistics own = analysis.pages[child];
    analysis.pages[parentIndex(child)] += own;
  }
}

}  // namespace

VirtualTextureRuntime::VirtualTextureRuntime(const VirtualTextureReader& reader,
                                             const RuntimeOptions& options)
    : reader_(reader),
      options_(options),
      // The root is always locked: every lookup falls back to it, so it must never leave.
      pageCache_(options.framesX, options.framesY, std::max(1u, options.lockedLevels)),
      table_(requirePageTablesFit(reader.path(), reader.description().levelCount)) {
  const TextureDescription& d = reader.description();
  if (options.priority.ancestors == AncestorStrategy::kGainSsim && !reader.hasAncestorErrors())
    throw InputError(reader.path(),
                     "'ancestors': 'gain_ssim' needs the ancestor errors that `vt build "
                     "--ancestor-errors` stores, and this file has none");
  cache_ = emptyCache(d, options.framesX, options.framesY, options.decoding);
  cache_.indirection = IndirectionTable(d.levelCount);
  for (uint32_t m = 0; m < d.levelCount; ++m)
    std::ranges::copy(table_.level(m), cache_.indirection.level(m).begin());
  // The root first: every lookup then finds a resident page.
  uint64_t evicted = 0;
  insert(0, reader.readStoredPage(PageId{}), evicted);
  syncIndirection();
}

void VirtualTextureRuntime::insert(uint64_t page, std::span<const std::byte> stored,
                                   uint64_t& evicted) {
  if (pageCache_.contains(page)) return;
  const auto placement = pageCache_.insert(page);
  if (!placement) return;  // every frame holds a locked page
  if (placement->evicted) {
    table_.evict(fromAbsoluteIndex(*placement->evicted));
    ++evicted;
  }
  table_.insert(fromAbsoluteIndex(page), placement->frame);
  storePage(cache_, placement->frame.x, placement->frame.y, stored);
}

void VirtualTextureRuntime::syncIndirection() {
  // Copy the subtrees the table changed, level by level, into the indirection table.
  for (const PageId root : table_.takeChanges()) {
    for (uint32_t m = root.level; m < table_.levelCount(); ++m) {
      const uint32_t shift = m - root.level;
      const uint64_t side = uint64_t{1} << shift, stride = pagesPerSide(m);
      for (uint64_t y = 0; y < side; ++y) {
        const uint64_t first =
            ((uint64_t{root.y} << shift) + y) * stride + (uint64_t{root.x} << shift);
        std::copy_n(table_.level(m).begin() + static_cast<long>(first), side,
                    cache_.indirection.level(m).begin() + static_cast<long>(first));
      }
    }
  }
  cache_.residentPages = pageCache_.residentPages();
}

void VirtualTextureRuntime::preload(std::span<const uint64_t> pages) {
  uint64_t evicted = 0;
  for (const uint64_t page : pages)
    if (reader_.contains(fromAbsoluteIndex(page)))
      insert(page, reader_.readStoredPage(fromAbsoluteIndex(page)), evicted);
  syncIndirection();
}

std::pair<uint64_t, uint64_t> VirtualTextureRuntime::apply(std::vector<StreamedPage> pages) {
  uint64_t applied = 0, evicted = 0;
  for (const StreamedPage& streamed : pages) {
    if (pageCache_.contains(streamed.page)) continue;
    insert(streamed.page, streamed.stored, evicted);
    applied += pageCache_.contains(streamed.page);
  }
  syncIndirection();
  return {applied, evicted};
}

bool VirtualTextureRuntime::needsDepth() const {
  return options_.priority.heuristic.uses(PriorityFactor::kDistance);
}

std::vector<StreamRequest> VirtualTextureRuntime::analyze(
    std::span<const glm::uvec4> need, std::span<const float> depth, int width, int height,
    bool need8, uint64_t frameNumber, FrameStatistics& statistics, const Prediction& prediction) {
  const Heuristic& heuristic = options_.priority.heuristic;
  AnalysisOptions analysisOptions;
  analysisOptions.need8 = need8;
  analysisOptions.depth = needsDepth();
  analysisOptions.centreWeight = heuristic.uses(PriorityFactor::kWeightedPixel);
  if (heuristic.uses(PriorityFactor::kHotSpot))
    analysisOptions.hotSpot = prediction.hotSpot.value_or(
        glm::vec2(static_cast<float>(width), static_cast<float>(height)) * 0.5f);
  const NeedBufferAnalysis analysis =
      analyzeNeedBuffer(need, depth, width, height, analysisOptions);
  // The LookAhead pass adds its pages' statistics (its depth is not read: Distance ranks by the
  // drawn frame); with prefetch they are ranked on their own, after the drawn frame's.
  NeedBufferAnalysis combined = analysis;
  NeedBufferAnalysis ahead;
  if (!prediction.lookAheadNeed.empty()) {
    AnalysisOptions predicted = analysisOptions;
    predicted.depth = false;
    ahead = analyzeNeedBuffer(prediction.lookAheadNeed, {}, width, height, predicted);
    if (!options_.lookAheadPrefetch)
      for (const auto& [page, s] : ahead.pages)
        for (uint32_t k = 0; k < options_.lookAheadWeight; ++k) combined.pages[page] += s;
  }

  statistics.coveredPixels = analysis.coveredPixels;
  statistics.neededPages = analysis.pages.size();
  std::vector<uint64_t> residentNeeded;
  for (const auto& [page, pageStatistics] : analysis.pages) {
    if (pageCache_.contains(page)) {
      ++statistics.hits;
      statistics.hitPixels += pageStatistics.pixels;
      residentNeeded.push_back(page);
    } else {
      ++statistics.misses;
    }
    if (options_.trilinearParents && levelOfAbsoluteIndex(page) > 0) {
      if (pageCache_.contains(parentIndex(page))) residentNeeded.push_back(parentIndex(page));
    }
  }
  // Touch in page order, each page once: the LRU order, and so every later eviction, is
  // deterministic.
  std::sort(residentNeeded.begin(), residentNeeded.end());
  residentNeeded.erase(std::unique(residentNeeded.begin(), residentNeeded.end()),
                       residentNeeded.end());
  for (const uint64_t page : residentNeeded) pageCache_.touch(page);
  if (options_.trilinearParents) addTrilinearParents(combined);

  PriorityOptions priority = options_.priority;
  priority.seed = frameSeed(frameNumber);
  const NoiseValues noise = [this](PageId page) {
    return reader_.contains(page) ? reader_.noiseValue(page) : 0.0f;
  };
  const AncestorErrors ancestorErrors = fileAncestorErrors();
  std::vector<StreamRequest> requests =
      prioritizePages(combined, table_, noise, priority, ancestorErrors);
  if (options_.lodBiasBacklog > 0 && statistics.misses > options_.lodBiasBacklog) {
    NeedBufferAnalysis coarser;
    coarser.coveredPixels = combined.coveredPixels;
    for (const auto& [page, s] : combined.pages) {
      const bool up = levelOfAbsoluteIndex(page) > 0 && !pageCache_.contains(page);
      coarser.pages[up ? parentIndex(page) : page] += s;
    }
    std::vector<StreamRequest> biased =
        prioritizePages(coarser, table_, noise, priority, ancestorErrors);
    std::unordered_set<uint64_t> requested;
    for (const StreamRequest& r : biased) requested.insert(r.page);
    for (const StreamRequest& r : requests)
      if (requested.insert(r.page).second) biased.push_back(r);
    requests = std::move(biased);
  }
  if (options_.lookAheadPrefetch && !ahead.pages.empty()) {
    if (options_.trilinearParents) addTrilinearParents(ahead);
    std::unordered_set<uint64_t> requested;
    for (const StreamRequest& r : requests) requested.insert(r.page);
    for (const StreamRequest& r : prioritizePages(ahead, table_, noise, priority, ancestorErrors))
      if (requested.insert(r.page).second) requests.push_back(r);
  }
  if (options_.keepAnalysis) {
    lastAnalysis_ = std::move(combined);
    lastFrame_ = frameNumber;
  }
  // Pages the file does not store (outside a sparse layout) cannot be streamed.
  std::erase_if(requests, [this](const StreamRequest& r) {
    return !reader_.contains(fromAbsoluteIndex(r.page));
  });
  statistics.requested = requests.size();
  statistics.resident = pageCache_.size();
  return requests;
}

AncestorErrors VirtualTextureRuntime::fileAncestorErrors() const {
  if (!reader_.hasAncestorErrors()) return {};
  // A page the file does not store (outside a sparse layout) shows its finest stored ancestor s:
  // its error through a level is s's, and zero from s's level on.
  return [this](PageId page) {
    PageId stored = page;
    while (!reader_.contains(stored)) stored = parent(stored);
    const std::span<const float> errors = reader_.ancestorErrors(stored);
    std::vector<double> row(page.level, 0.0);
    for (uint32_t level = 0; level < stored.level; ++level)
      row[level] = static_cast<double>(errors[level]);
    return row;
  };
}

std::vector<std::pair<std::string, double>> VirtualTextureRuntime::priorityTerms(
    uint64_t page) const {
  PriorityOptions priority = options_.priority;
  priority.seed = frameSeed(lastFrame_);
  const NoiseValues noise = [this](PageId p) {
    return reader_.contains(p) ? reader_.noiseValue(p) : 0.0f;
  };
  return vt::priorityTerms(page, lastAnalysis_, table_, noise, priority);
}

}  // namespace vt
