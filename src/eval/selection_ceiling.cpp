#include "eval/selection_ceiling.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "reference/recolor.h"

namespace vt {
namespace {

uint32_t levelOf(glm::u16vec4 entry) { return entry.z; }

// The pages whose arrival would change what a pixel reads: for each page it reads, every page
// from the level after its resident one down to the page itself (absolute indices, each once).
void pagesThatChange(const reference::PagesRead& read, const IndirectionTable& table,
                     std::vector<uint64_t>& out) {
  out.clear();
  for (const PageId page : {read.first, read.second}) {
    for (uint32_t level = levelOf(table.entry(page)) + 1; level <= page.level; ++level) {
      const uint64_t index = absoluteIndex(ancestorAt(page, level));
      if (std::find(out.begin(), out.end(), index) == out.end()) out.push_back(index);
    }
    if (read.second == read.first) break;
  }
}

// Copies frame (fx, fy)'s texels, and its blocks for a block format, between two caches of the
// same size.
void copyFrame(const CacheState& from, CacheState& to, uint32_t fx, uint32_t fy) {
  const uint32_t side = from.description.storedPageSide();
  for (uint32_t y = 0; y < side; ++y) {
    const size_t at = ((size_t{fy} * side + y) * from.widthTexels + size_t{fx} * side) * 4;
    std::memcpy(to.texels.data() + at, from.texels.data() + at, size_t{side} * 4);
  }
  if (!isBlockCompressed(from.description.format)) return;
  const size_t bytes = blockBytes(from.description.format);
  const uint32_t perRow = from.widthTexels / 4, pageBlocks = side / 4;
  for (uint32_t by = 0; by < pageBlocks; ++by) {
    const size_t at = ((size_t{fy} * pageBlocks + by) * perRow + size_t{fx} * pageBlocks) * bytes;
    std::memcpy(to.blocks.data() + at, from.blocks.data() + at, size_t{pageBlocks} * bytes);
  }
}

}  // namespace

struct CeilingSelection::Candidate {
  uint64_t index = 0;  // absolute
  PageId page;
  uint32_t pixels = 0;  // of the next frame whose reads it could change
  std::vector<std::byte> stored;
  std::vector<uint32_t> where;  // those pixels
  glm::ivec2 low{std::numeric_limits<int>::max()}, high{std::numeric_limits<int>::min()};
};

CeilingSelection::CeilingSelection(const VirtualTextureReader& reader,
                                   const RenderSettings& settings, uint32_t candidates,
                                   CeilingPool pool)
    : reader_(reader),
      settings_(settings),
      maxCandidates_(candidates),
      pool_(pool),
      ssim_(settings.viewport.width, settings.viewport.height) {
  settings_.debugChannels = false;
}

CeilingSelection::~CeilingSelection() = default;

std::vector<std::pair<PageId, glm::u16vec4>> CeilingSelection::place(const Candidate& candidate,
                                                                     glm::uvec2 frame) {
  std::vector<std::pair<PageId, glm::u16vec4>> changed;
  IndirectionTable& table = trial_->indirection;
  const uint32_t level = candidate.page.level;
  if (levelOf(table.entry(candidate.page)) >= level) return changed;  // served at its level
  storePage(*trial_, frame.x, frame.y, candidate.stored);
  const glm::u16vec4 entry(frame.x, frame.y, level, 0);
  std::vector<PageId> stack{candidate.page};
  while (!stack.empty()) {
    const PageId page = stack.back();
    stack.pop_back();
    const glm::u16vec4 old = table.entry(page);
    if (levelOf(old) >= level) continue;  // a page of its own subtree serves it, and below
    changed.emplace_back(page, old);
    table.set(page, entry);
    if (page.level + 1 < table.levelCount())
      for (uint32_t k = 0; k < 4; ++k)
        stack.push_back({2 * page.x + (k & 1), 2 * page.y + (k >> 1), page.level + 1});
  }
  return changed;
}

void CeilingSelection::undo(const std::vector<std::pair<PageId, glm::u16vec4>>& changed) {
  for (auto it = changed.rbegin(); it != changed.rend(); ++it)
    trial_->indirection.set(it->first, it->second);
}

// What each pixel of the next frame reads, the frames it reads them from, and how many pixels
// each page that would change a read touches. Neighbouring pixels mostly read the same pages: a
// run of them is looked up once.
struct NextFrameSurvey {
  std::vector<reference::PagesRead> reads;
  std::vector<uint8_t> frameRead;  // per cache frame
  std::unordered_map<uint64_t, uint32_t> pixelsOf;
};

namespace {

NextFrameSurvey survey(const CacheState& current, const Frame& next,
                       const RenderSettings& settings) {
  NextFrameSurvey s;
  s.reads = reference::pagesRead(next, current.description, settings);
  s.frameRead.assign(size_t{current.framesX} * current.framesY, 0);
  std::vector<uint64_t> pages;
  const reference::PagesRead* previous = nullptr;
  for (const reference::PagesRead& read : s.reads) {
    if (!read.covered) continue;
    if (previous == nullptr || !(read == *previous)) {
      pagesThatChange(read, current.indirection, pages);
      for (const PageId page : {read.first, read.second}) {
        const glm::u16vec4 e = current.indirection.entry(page);
        s.frameRead[size_t{e.y} * current.framesX + e.x] = 1;
      }
      previous = &read;
    }
    for (const uint64_t page : pages) ++s.pixelsOf[page];
  }
  return s;
}

}  // namespace

std::vector<CeilingSelection::Candidate> CeilingSelection::candidatesOf(
    const CacheState& current, const NextFrameSurvey& survey,
    std::span<const StreamRequest> requests) const {
  // The pool: the pages the frame's requests name and their missing ancestors, or (looking
  // further than any strategy can) whatever the next frame would read.
  std::unordered_set<uint64_t> pool;
  if (pool_ == CeilingPool::kRequests)
    for (const StreamRequest& request : requests) {
      const PageId page = fromAbsoluteIndex(request.page);
      for (uint32_t level = levelOf(current.indirection.entry(page)) + 1; level <= page.level;
           ++level)
        pool.insert(absoluteIndex(ancestorAt(page, level)));
    }
  std::vector<Candidate> candidates;
  for (const auto& [index, pixels] : survey.pixelsOf) {
    const PageId page = fromAbsoluteIndex(index);
    if (reader_.contains(page) && (pool_ == CeilingPool::kNextFrame || pool.contains(index)))
      candidates.push_back({index, page, pixels, {}, {}});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.pixels != b.pixels ? a.pixels > b.pixels : a.index < b.index;
  });
  if (candidates.size() > maxCandidates_) candidates.resize(maxCandidates_);

  // Each candidate's pixels, and the rectangle around them.
  std::unordered_map<uint64_t, size_t> candidateOf;
  for (size_t c = 0; c < candidates.size(); ++c) {
    candidateOf.emplace(candidates[c].index, c);
    candidates[c].stored = reader_.readStoredPage(candidates[c].page);
  }
  const reference::PagesRead* previous = nullptr;
  std::vector<uint64_t> pages;
  std::vector<size_t> mine;
  for (uint32_t i = 0; i < survey.reads.size(); ++i) {
    if (!survey.reads[i].covered) continue;
    if (previous == nullptr || !(survey.reads[i] == *previous)) {
      pagesThatChange(survey.reads[i], current.indirection, pages);
      mine.clear();
      for (const uint64_t page : pages)
        if (const auto found = candidateOf.find(page); found != candidateOf.end())
          mine.push_back(found->second);
      previous = &survey.reads[i];
    }
    for (const size_t c : mine) candidates[c].where.push_back(i);
  }
  const auto width = static_cast<uint32_t>(settings_.viewport.width);
  for (Candidate& c : candidates)
    for (const uint32_t pixel : c.where) {
      const glm::ivec2 at(static_cast<int>(pixel % width), static_cast<int>(pixel / width));
      c.low = glm::min(c.low, at);
      c.high = glm::max(c.high, at);
    }
  return candidates;
}

double CeilingSelection::tryCandidate(const Candidate& candidate, const Frame& next,
                                      glm::uvec2 frame) {
  const auto changed = place(candidate, frame);
  if (changed.empty()) return 0.0;
  shaded_.resize(candidate.where.size() * 4);
  reference::recolorPixels(next, *trial_, settings_, candidate.where, shaded_);
  const double gain = ssim_.gain(candidate.where, shaded_);
  undo(changed);
  return gain;
}

std::vector<std::pair<size_t, double>> CeilingSelection::pickGreedily(
    const std::vector<Candidate>& candidates, const Frame& next, std::span<const glm::uvec2> spare,
    uint32_t budget) {
  // Lazily: a pick changes the gain of the candidates whose pixels lie within a window of its
  // own only (the windows they touch, and the entries they read, are apart otherwise).
  const int reach = WindowSsim::kSide - 1;
  std::vector<double> gain(candidates.size(), 0.0);
  std::vector<uint8_t> fresh(candidates.size(), 0), taken(candidates.size(), 0);
  std::vector<std::pair<size_t, double>> picked;
  for (uint32_t round = 0; round < budget && picked.size() + 1 < spare.size(); ++round) {
    const glm::uvec2 frame = spare[picked.size()];
    size_t best = candidates.size();
    double bestGain = 0.0;
    for (size_t c = 0; c < candidates.size(); ++c) {
      if (taken[c]) continue;
      if (!fresh[c]) {
        gain[c] = tryCandidate(candidates[c], next, frame);
        fresh[c] = 1;
      }
      if (gain[c] > bestGain) {
        bestGain = gain[c];
        best = c;
      }
    }
    if (best == candidates.size()) break;  // nothing left raises the next frame
    const Candidate& b = candidates[best];
    for (size_t c = 0; c < candidates.size(); ++c) {
      const Candidate& other = candidates[c];
      if (glm::all(glm::lessThanEqual(other.low - reach, b.high)) &&
          glm::all(glm::lessThanEqual(b.low - reach, other.high)))
        fresh[c] = 0;
    }
    place(b, frame);
    shaded_.resize(b.where.size() * 4);
    reference::recolorPixels(next, *trial_, settings_, b.where, shaded_);
    ssim_.apply(b.where, shaded_);
    taken[best] = 1;
    picked.emplace_back(best, bestGain / static_cast<double>(ssim_.windowCount()));
  }
  return picked;
}

std::vector<StreamRequest> CeilingSelection::choose(const CacheState& current, const Frame& next,
                                                    std::span<const StreamRequest> requests,
                                                    uint32_t budget) {
  last_ = {};
  std::vector<StreamRequest> order(requests.begin(), requests.end());
  if (budget == 0 || next.triangle.empty()) return order;
  if (!trial_ || trial_->framesX != current.framesX || trial_->framesY != current.framesY)
    trial_ = std::make_unique<CacheState>(
        emptyCache(current.description, current.framesX, current.framesY, current.decoding));
  trial_->indirection = current.indirection;
  const NextFrameSurvey s = survey(current, next, settings_);
  const std::vector<Candidate> candidates = candidatesOf(current, s, requests);
  last_.candidates = static_cast<uint32_t>(candidates.size());

  // The frames the next frame reads are copied; the others hold the pages tried and picked.
  std::vector<glm::uvec2> spare;
  for (uint32_t fy = 0; fy < current.framesY; ++fy)
    for (uint32_t fx = 0; fx < current.framesX; ++fx) {
      if (s.frameRead[size_t{fy} * current.framesX + fx])
        copyFrame(current, *trial_, fx, fy);
      else if (spare.size() <= budget)
        spare.emplace_back(fx, fy);
    }
  if (candidates.empty() || spare.size() < 2) return order;

  // The next frame under the current cache state, and the picks against its reference.
  reference::recolor(next, *trial_, settings_, color_);
  ssim_.reset(next.color, color_);
  std::vector<StreamRequest> chosen;
  for (const auto& [c, gain] : pickGreedily(candidates, next, spare, budget)) {
    chosen.push_back({candidates[c].index, gain});
    last_.predictedGain += gain;
  }
  last_.picked = static_cast<uint32_t>(chosen.size());
  for (const StreamRequest& request : order)
    if (std::none_of(chosen.begin(), chosen.end(),
                     [&](const StreamRequest& c) { return c.page == request.page; }))
      chosen.push_back(request);
  return chosen;
}

}  // namespace vt
