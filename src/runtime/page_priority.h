#pragma once
// Page priority heuristics (thesis 4.2) and ancestor streaming (4.3): from one frame's needbuffer
// analysis and the page table, the pages to stream, most important first.
//
// A heuristic (runtime/heuristic.h) is a product of factors, written e.g. "pixelsum" or
// "pixelsum*noisevalue":
//   random         uniform in [0, 1), from a hash of the page and the frame's seed (4.2.2)
//   pixelsum       pixels that need the page (4.2.2)
//   distance       1 - mean window depth of those pixels: nearer is more important (4.2.2)
//   weightedpixel  pixels weighted by closeness to the screen centre (4.2.3.1)
//   hotspot        pixels weighted by closeness to the hot spot, the centre shifted by the
//                  camera's rotation (4.2.3.1); the caller places the hot spot
//   noisevalue     sum of NoiseValues from the page up to its resident ancestor (4.2.3.2)
//   mipgap         needed level minus resident level, as id Tech 5 ranks requests
// Ties are broken by the smaller absolute page index, so the order is deterministic.
//
// Ancestor streaming (4.3) adds every non-resident ancestor of a needed page, with the sum of its
// children's priorities:
//   intern  an ancestor is streamed before its descendants; otherwise priority decides
//   extern  coarser levels before finer ones; within a level, priority decides
//   with NoiseValue skipping (extern), an ancestor is added only through a child whose NoiseValue
//   (against that ancestor) reaches the threshold (default: the texture's mean NoiseValue).
//   gain    beyond the thesis: greedily by the error each page removes, the heuristic's value of
//           each needed page weighting its pixels (runtime/error_gain_order.h), the error
//           through an ancestor the sum of the NoiseValues up to it
//   gain_ssim  the same with the error through each ancestor as `vt build --ancestor-errors`
//           measured it (1 - SSIM on the evaluations' windows, build/ancestor_error.h)

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "runtime/heuristic.h"
#include "runtime/needbuffer_analysis.h"
#include "runtime/page_table.h"

namespace vt {

enum class AncestorStrategy { kNone, kIntern, kExtern, kGain, kGainSsim };

inline constexpr EnumNames<AncestorStrategy, 5> kAncestorStrategyNames = {{
    {AncestorStrategy::kNone, "none"},
    {AncestorStrategy::kIntern, "intern"},
    {AncestorStrategy::kExtern, "extern"},
    {AncestorStrategy::kGain, "gain"},
    {AncestorStrategy::kGainSsim, "gain_ssim"},
}};

struct PriorityOptions {
  Heuristic heuristic;  // pixelsum
  AncestorStrategy ancestors = AncestorStrategy::kNone;
  bool noiseValueSkipping = false;
  float noiseThreshold = 0.0f;  // used with noiseValueSkipping
  uint64_t seed = 0;            // for `random`: the frame number, say
};

struct StreamRequest {
  uint64_t page;  // absolute index
  double priority;
  friend bool operator==(const StreamRequest&, const StreamRequest&) = default;
};

// The NoiseValue of a stored page (VirtualTextureReader::noiseValue, or a test's table).
using NoiseValues = std::function<float(PageId)>;
// Page q's row E_q(0), ..., E_q(q.level - 1): its error shown through its ancestor on each coarser
// level (gain_ssim: the file's ancestor errors, VirtualTextureReader::ancestorErrors).
using AncestorErrors = std::function<std::vector<double>(PageId page)>;

// Throws std::invalid_argument naming an unknown strategy.
// none, intern, extern, gain, gain_ssim
AncestorStrategy parseAncestorStrategy(const std::string& name);
std::string toString(AncestorStrategy strategy);

// The value of each factor of the heuristic for a page the analysis holds, in the heuristic's
// order (the priority is their product); empty for other pages, such as ancestors, whose priority
// is the sum of their children's. For inspecting a frame's priority queue.
std::vector<std::pair<std::string, double>> priorityTerms(uint64_t page,
                                                          const NeedBufferAnalysis& analysis,
                                                          const PageTable& table,
                                                          const NoiseValues& noise,
                                                          const PriorityOptions& options);

// Non-resident needed pages (and ancestors, by the strategy), in the order to stream them.
// gain_ssim needs `ancestorErrors` (std::invalid_argument without).
std::vector<StreamRequest> prioritizePages(const NeedBufferAnalysis& analysis,
                                           const PageTable& table, const NoiseValues& noise,
                                           const PriorityOptions& options,
                                           const AncestorErrors& ancestorErrors = {});

}  // namespace vt
