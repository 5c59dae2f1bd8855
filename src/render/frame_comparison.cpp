#include "render/frame_comparison.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "format/page_address.h"
#include "shader/needbuffer.h"

namespace vt {
namespace {

// A reason's bit number (the index of reasonName, widthUnit and the per-reason counts).
constexpr int bitOf(uint8_t reason) { return std::countr_zero(static_cast<unsigned>(reason)); }

// The observed needbuffer value as a page, or none for "no geometry". A value that names no page
// of the texture (a page beyond its level, as a missing clamp of s = 1.0 writes) is still read as
// the page it names, so that it lies outside every set by that many pages.
std::optional<PageId> observedPage(glm::uvec4 need, bool need8) {
  if (const std::optional<PageId> page = decodeNeed(need, need8)) return page;
  if (need == needClearValue(need8)) return std::nullopt;
  if (need8) {
    if (glm::any(glm::greaterThan(need, glm::uvec4(255))) || need.z > kMaxLevel)
      return std::nullopt;
    return PageId{need.x + (need.w & 15u) * 256u, need.y + (need.w >> 4) * 256u, need.z};
  }
  if (need.w == 0 || need.z > kMaxLevel) return std::nullopt;
  return PageId{need.x, need.y, need.z};
}

// Pages by which `page` lies outside the alternative's range at its level (0: inside).
double pagesOutside(const Alternative& a, const PageId& page) {
  const int m = static_cast<int>(page.level);
  const auto outside = [](int v, int lo, int hi) {
    return v < lo ? lo - v : (v > hi ? v - hi : 0);
  };
  return std::max(outside(static_cast<int>(page.x), pageAt(a.uvLo.x, m), pageAt(a.uvHi.x, m)),
                  outside(static_cast<int>(page.y), pageAt(a.uvLo.y, m), pageAt(a.uvHi.y, m)));
}

double colourOutside(glm::u8vec4 lo, glm::u8vec4 hi, const uint8_t* color) {
  double worst = 0;
  for (int c = 0; c < 4; ++c) {
    const int v = color[c];
    worst =
        std::max(worst, static_cast<double>(v < lo[c] ? lo[c] - v : (v > hi[c] ? v - hi[c] : 0)));
  }
  return worst;
}

struct Verdict {
  bool explained = false;
  int reason = 0;  // bit number
  double widenBy = 0;
};

// How far a failed verdict is from holding, across reasons whose units differ: a colour off with
// the needbuffer right is nearer than a page off, a page off nearer than a level off, a level off
// nearer than another triangle or none.
int distanceRank(int reason) {
  switch (reason) {
    case bitOf(kReasonFilter):
      return 0;
    case bitOf(kReasonAttributes):
      return 1;
    case bitOf(kReasonLod):
      return 2;
    default:
      return 3;  // kReasonCoverage, kReasonDepth
  }
}

// Whether the alternative holds the observed value; if not, what would have to widen.
Verdict judge(const Alternative& a, std::optional<PageId> page, const uint8_t* color,
              glm::uvec4 need, glm::uvec4 oracleNeed, bool need8) {
  if (a.triangle < 0) {
    if (page) return {false, bitOf(kReasonCoverage), 1};
    const bool clear = need == needClearValue(need8) && color[0] == 0 && color[1] == 0 &&
                       color[2] == 0 && color[3] == 0;
    return clear ? Verdict{true, 0, 0} : Verdict{false, bitOf(kReasonCoverage), 1};
  }
  if (!page) return {false, bitOf(kReasonCoverage), 1};
  if (page->level < a.levelLo || page->level > a.levelHi) {
    const double levels =
        page->level < a.levelLo ? a.levelLo - page->level : page->level - a.levelHi;
    return {false, bitOf(kReasonLod), levels};
  }
  if (const double pages = pagesOutside(a, *page); pages > 0)
    return {false, bitOf(kReasonAttributes), pages};
  if (const double units = colourOutside(a.colorLo, a.colorHi, color); units > 0)
    return {false, bitOf(kReasonFilter), units};
  // Inside: the narrowest reason that admits it.
  if (a.reasons != 0) return {true, bitOf(a.reasons), 0};
  if (need != oracleNeed)
    return {true,
            page->level != decodeNeed(oracleNeed, need8).value_or(*page).level
                ? bitOf(kReasonLod)
                : bitOf(kReasonAttributes),
            0};
  if (colourOutside(a.filterLo, a.filterHi, color) == 0) return {true, bitOf(kReasonFilter), 0};
  return {true, bitOf(kReasonAttributes), 0};
}

// The oracle's one value as an alternative (a pinned model): the page range of its need and its
// colour.
Alternative pointAlternative(const Frame& oracle, size_t i, bool need8) {
  Alternative a;
  const std::optional<PageId> page = decodeNeed(oracle.need[i], need8);
  if (!page) return a;  // triangle -1: clear
  // A frame built from images alone (the public API's) has no triangle image: any covered pixel
  // counts as triangle 0, which only the clear alternative tells apart.
  a.triangle = i < oracle.triangle.size() && oracle.triangle[i] >= 0 ? oracle.triangle[i] : 0;
  a.levelLo = a.levelHi = static_cast<uint8_t>(page->level);
  const float scale = std::ldexp(1.0f, -static_cast<int>(page->level));
  a.uvLo = glm::vec2(static_cast<float>(page->x) * scale, static_cast<float>(page->y) * scale);
  a.uvHi = a.uvLo;
  const uint8_t* c = &oracle.color[i * 4];
  a.colorLo = a.colorHi = a.filterLo = a.filterHi = glm::u8vec4(c[0], c[1], c[2], c[3]);
  return a;
}

// The unorm8 values of one channel some alternative admits, as 256 bits.
class ChannelValues {
 public:
  void insert(int lo, int hi) {
    for (int w = 0; w < 4; ++w) {
      const int first = std::max(lo, 64 * w), last = std::min(hi, 64 * w + 63);
      if (first > last) continue;
      const int bits = last - first + 1;
      const uint64_t run = bits == 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1;
      words_[static_cast<size_t>(w)] |= run << (first - 64 * w);
    }
  }
  int count() const {
    int n = 0;
    for (const uint64_t word : words_) n += std::popcount(word);
    return n;
  }

 private:
  std::array<uint64_t, 4> words_{};
};

// The pages of one level an alternative admits: columns x0..x1, rows y0..y1.
struct PageRange {
  int x0, x1, y0, y1;
};

PageRange pageRange(const Alternative& a, int level) {
  return {pageAt(a.uvLo.x, level), pageAt(a.uvHi.x, level), pageAt(a.uvLo.y, level),
          pageAt(a.uvHi.y, level)};
}

// How many pages lie in at least one range: the plane cut at every range's edges into cells, each
// cell counted once when a range holds it.
uint64_t pagesInUnion(std::span<const PageRange> ranges) {
  if (ranges.size() == 1)
    return static_cast<uint64_t>(ranges[0].x1 - ranges[0].x0 + 1) *
           static_cast<uint64_t>(ranges[0].y1 - ranges[0].y0 + 1);
  std::vector<int> xs, ys;
  for (const PageRange& r : ranges) {
    xs.insert(xs.end(), {r.x0, r.x1 + 1});
    ys.insert(ys.end(), {r.y0, r.y1 + 1});
  }
  for (std::vector<int>* cuts : {&xs, &ys}) {
    std::sort(cuts->begin(), cuts->end());
    cuts->erase(std::unique(cuts->begin(), cuts->end()), cuts->end());
  }
  uint64_t pages = 0;
  for (size_t i = 0; i + 1 < xs.size(); ++i)
    for (size_t j = 0; j + 1 < ys.size(); ++j) {
      const bool held = std::any_of(ranges.begin(), ranges.end(), [&](const PageRange& r) {
        return r.x0 <= xs[i] && xs[i] <= r.x1 && r.y0 <= ys[j] && ys[j] <= r.y1;
      });
      if (held)
        pages +=
            static_cast<uint64_t>(xs[i + 1] - xs[i]) * static_cast<uint64_t>(ys[j + 1] - ys[j]);
    }
  return pages;
}

// pixelSetWidths of a set of one alternative: the same counts without the unions.
SetWidths alternativeWidths(const Alternative& a) {
  if (a.triangle < 0) return {};
  const int lastLevel = std::min<int>(a.levelHi, kMaxLevel);
  if (a.levelLo > lastLevel) return {};
  SetWidths widths;
  widths.covered = 1;
  for (int c = 0; c < 4; ++c)
    widths.colorWidthSum += a.colorHi[c] >= a.colorLo[c] ? a.colorHi[c] - a.colorLo[c] : -1;
  widths.colorWidthSum /= 4;
  widths.levelSum = static_cast<uint64_t>(lastLevel - a.levelLo + 1);
  for (int m = a.levelLo; m <= lastLevel; ++m) {
    const PageRange r = pageRange(a, m);
    widths.pageSum += pagesInUnion(std::span<const PageRange>(&r, 1));
  }
  return widths;
}

double mean(double sum, uint64_t count) { return count ? sum / static_cast<double>(count) : 0.0; }

}  // namespace

double SetWidths::meanColorWidth() const { return mean(colorWidthSum, covered); }
double SetWidths::meanLevels() const { return mean(static_cast<double>(levelSum), covered); }
double SetWidths::meanPages() const { return mean(static_cast<double>(pageSum), covered); }

void SetWidths::add(const SetWidths& other) {
  covered += other.covered;
  colorWidthSum += other.colorWidthSum;
  levelSum += other.levelSum;
  pageSum += other.pageSum;
}

SetWidths pixelSetWidths(const ResultSets& sets, size_t pixel) {
  if (sets.empty()) return {};
  const std::span<const Alternative> set(sets.alternatives.data() + sets.offsets[pixel],
                                         sets.offsets[pixel + 1] - sets.offsets[pixel]);
  if (set.empty()) return {};  // not built (ResultSets::judged)
  if (set.size() == 1) return alternativeWidths(set[0]);
  std::array<ChannelValues, 4> channels;
  uint32_t levels = 0;  // bit m: level m admitted
  for (const Alternative& a : set) {
    for (size_t c = 0; c < 4; ++c)
      channels[c].insert(a.colorLo[static_cast<int>(c)], a.colorHi[static_cast<int>(c)]);
    if (a.triangle >= 0)
      for (int m = a.levelLo; m <= std::min<int>(a.levelHi, kMaxLevel); ++m) levels |= 1u << m;
  }
  if (levels == 0) return {};  // no triangle: the pixel stays empty
  SetWidths widths;
  widths.covered = 1;
  for (const ChannelValues& values : channels) widths.colorWidthSum += values.count() - 1;
  widths.colorWidthSum /= 4;
  widths.levelSum = static_cast<uint64_t>(std::popcount(levels));
  std::vector<PageRange> ranges;
  for (int m = 0; m <= static_cast<int>(kMaxLevel); ++m) {
    if ((levels & (1u << m)) == 0) continue;
    ranges.clear();
    for (const Alternative& a : set)
      if (a.triangle >= 0 && a.levelLo <= m && m <= a.levelHi) ranges.push_back(pageRange(a, m));
    widths.pageSum += pagesInUnion(ranges);
  }
  return widths;
}

SetWidths setWidths(const ResultSets& sets, std::span<const glm::uvec4> need, bool need8) {
  SetWidths widths;
  if (sets.empty()) {
    for (const glm::uvec4& value : need)
      if (decodeNeed(value, need8)) widths.add({1, 0.0, 1, 1});
    return widths;
  }
  for (size_t i = 0; i + 1 < sets.offsets.size(); ++i) widths.add(pixelSetWidths(sets, i));
  return widths;
}

const char* widthUnit(int reason) {
  static const char* const kUnits[kResultReasons] = {"triangle", "triangle", "pages", "levels",
                                                     "1/255"};
  return reason >= 0 && reason < kResultReasons ? kUnits[reason] : "";
}

glm::u8vec3 reasonShade(int reason) {
  switch (reason) {
    case bitOf(kReasonCoverage):
      return {60, 120, 255};  // blue
    case bitOf(kReasonDepth):
      return {0, 220, 220};  // cyan
    case bitOf(kReasonAttributes):
      return {0, 200, 0};  // green
    case bitOf(kReasonLod):
      return {255, 220, 0};  // yellow
    case bitOf(kReasonFilter):
      return {180, 0, 255};  // violet
    default:
      return {255, 0, 0};  // unexplained: red
  }
}

FrameComparison compareFrames(const Frame& oracle, std::span<const uint8_t> color,
                              std::span<const glm::uvec4> need, bool need8) {
  return compareFrames(oracle, oracle.sets, color, need, need8);
}

FrameComparison compareFrames(const Frame& oracle, const ResultSets& sets,
                              std::span<const uint8_t> color, std::span<const glm::uvec4> need,
                              bool need8) {
  const size_t pixels = oracle.need.size();
  if (color.size() != pixels * 4 || need.size() != pixels)
    throw std::invalid_argument("compareFrames: frames of different sizes");
  if (!sets.empty() && sets.offsets.size() != pixels + 1)
    throw std::invalid_argument("compareFrames: result sets of another size");
  FrameComparison result;
  result.pixels = pixels;
  result.colorDifferenceImage.assign(pixels * 4, 255);
  result.classificationImage.assign(pixels * 4, 255);
  const int width = oracle.viewport.width, height = oracle.viewport.height;
  uint64_t differenceSum = 0;
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      const size_t i =
          static_cast<size_t>(py) * static_cast<size_t>(width) + static_cast<size_t>(px);
      const size_t out = (static_cast<size_t>(height - 1 - py) * static_cast<size_t>(width) +
                          static_cast<size_t>(px)) *
                         4;
      int largest = 0;
      for (size_t c = 0; c < 4; ++c) {
        const int difference = std::abs(int{color[i * 4 + c]} - int{oracle.color[i * 4 + c]});
        largest = std::max(largest, difference);
        differenceSum += static_cast<uint64_t>(difference);
        if (c < 3)
          result.colorDifferenceImage[out + c] =
              static_cast<uint8_t>(std::min(255, difference * 16));
      }
      result.maxColorDifference = std::max(result.maxColorDifference, largest);
      const bool isAmbiguous = ambiguous(sets, i);
      result.ambiguous += isAmbiguous;
      glm::u8vec3 shade = isAmbiguous ? glm::u8vec3(64, 64, 64) : glm::u8vec3(0, 0, 0);
      if (need[i] == oracle.need[i] && largest == 0) {
        ++result.identical;
      } else {
        const std::optional<PageId> page = observedPage(need[i], need8);
        Verdict best{false, -1, std::numeric_limits<double>::infinity()};
        const auto consider = [&](const Alternative& a) {
          const Verdict v = judge(a, page, &color[i * 4], need[i], oracle.need[i], need8);
          if (v.explained && !best.explained) best = v;
          if (!best.explained &&
              (best.reason < 0 || distanceRank(v.reason) < distanceRank(best.reason) ||
               (distanceRank(v.reason) == distanceRank(best.reason) && v.widenBy < best.widenBy)))
            best = v;
        };
        if (sets.empty()) {
          consider(pointAlternative(oracle, i, need8));
        } else if (!sets.built(i)) {
          // Built against a judged frame that was identical here: another frame is compared.
          throw std::invalid_argument(
              "compareFrames: the result sets were built against another frame (pixel " +
              std::to_string(i) + " differs and has none)");
        } else {
          for (uint32_t k = sets.offsets[i]; k < sets.offsets[i + 1]; ++k)
            consider(sets.alternatives[k]);
        }
        const size_t r = static_cast<size_t>(std::max(best.reason, 0));
        if (best.explained) {
          ++result.explained;
          ++result.explainedBy[r];
          shade = reasonShade(static_cast<int>(r));
        } else {
          ++result.unexplained;
          ++result.unexplainedBy[r];
          result.widenBy[r] = std::max(result.widenBy[r], best.widenBy);
          result.needMismatched += need[i] != oracle.need[i];
          if (result.unexplainedPixels.size() < kListedMismatches)
            result.unexplainedPixels.push_back({i, static_cast<int>(r), best.widenBy});
          shade = reasonShade(-1);
        }
      }
      for (size_t c = 0; c < 3; ++c)
        result.classificationImage[out + c] = shade[static_cast<int>(c)];
    }
  result.meanColorDifference =
      pixels ? static_cast<double>(differenceSum) / static_cast<double>(pixels * 4) : 0.0;
  return result;
}

void accumulate(FrameComparison& total, const FrameComparison& frame) {
  total.pixels += frame.pixels;
  total.identical += frame.identical;
  total.explained += frame.explained;
  total.unexplained += frame.unexplained;
  total.ambiguous += frame.ambiguous;
  total.needMismatched += frame.needMismatched;
  for (size_t r = 0; r < kResultReasons; ++r) {
    total.explainedBy[r] += frame.explainedBy[r];
    total.unexplainedBy[r] += frame.unexplainedBy[r];
    total.widenBy[r] = std::max(total.widenBy[r], frame.widenBy[r]);
  }
  total.maxColorDifference = std::max(total.maxColorDifference, frame.maxColorDifference);
}

}  // namespace vt
