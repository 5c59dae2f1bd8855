#pragma once
// One configuration of the streaming system as chapter 4 of the thesis compares them: everything
// that decides which pages reach the cache and when. With a fixed budget of pages per frame
// (4.1.1) two configurations differ only in how well they choose.
//
// The JSON form uses the names of `vt fly`'s options, e.g.
//   { "name": "HotSpot x NoiseValue, LookAhead", "heuristic": "hotspot*noisevalue",
//     "lookahead": "stopfix", "budget": 5, "ancestors": "extern", "noise_skipping": true,
//     "locked_levels": 4, "need_scale": 4, "trilinear_parents": true, "seed": 3 }
// Keys left out keep their defaults (below, or the defaults given to fromJson); unknown keys and
// values out of range are errors.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "common/enum_names.h"
#include "format/texture_description.h"
#include "runtime/page_priority.h"
#include "scene/camera_motion.h"

namespace vt {

// How the pages to stream are chosen: by the heuristic and ancestor strategy (the runtime's own
// requests), or by the ceiling of selection, which looks at the next frame
// (eval/selection_ceiling.h; only an evaluation, which draws every view, can fly it), among the
// pages the requests name and their ancestors, or among every page the next frame reads.
enum class PageSelection { kHeuristic, kCeiling, kCeilingNextFrame };
inline constexpr EnumNames<PageSelection, 3> kPageSelectionNames = {{
    {PageSelection::kHeuristic, "heuristic"},
    {PageSelection::kCeiling, "ceiling"},
    {PageSelection::kCeilingNextFrame, "ceiling_next_frame"},
}};

struct FlightConfiguration {
  std::string name;     // label in tables and plots; empty: label() describes the settings
  Heuristic heuristic;  // pixelsum; runtime/page_priority.h
  AncestorStrategy ancestors = AncestorStrategy::kNone;
  bool noiseSkipping = false;
  float noiseThreshold = -1.0f;  // NoiseValueSkipping; negative: the texture's mean NoiseValue
  LookAhead lookAhead = LookAhead::kNone;
  // The LookAhead camera's pages merged with the drawn frame's (the thesis), or prefetched into
  // the slots the drawn frame's requests leave (runtime/virtual_texture_runtime.h); JSON
  // "lookahead_pages": "merged" or "prefetch", which needs a LookAhead camera.
  bool lookAheadPrefetch = false;
  // Beyond the thesis (runtime/virtual_texture_runtime.h): each merged LookAhead pixel counts
  // this many times (JSON "lookahead_weight", 1 to 16); when more than lodBiasBacklog needed pages
  // are missing, missing pages are requested one level coarser first (JSON "lod_bias_backlog",
  // 0: off).
  uint32_t lookAheadWeight = 1;
  uint32_t lodBiasBacklog = 0;
  HotSpotMode hotSpot = HotSpotMode::kShifted;
  uint32_t budget = 10;           // pages streamed per frame
  uint64_t budgetBytes = 0;       // or, when not zero, bytes per frame at the pages' stored size
                                  // (runtime/page_streamer.h: FrameBudget); JSON "budget_bytes"
  uint32_t latency = 0;           // frames between a request and its page's arrival
  uint32_t cacheFrames = 16;      // the cache holds cacheFrames x cacheFrames frames
  uint64_t cacheBytes = 0;        // or, when not zero, as many N x N frames as fit in these bytes
                                  // at the pages' stored size: compressed pages fit more frames
                                  // (cacheFramesFor); JSON "cache_bytes"
  uint32_t lockedLevels = 0;      // levels 0..K-1 never leave the cache (4.3.1)
  uint32_t initialLevels = 3;     // levels 0..K-1 loaded before the first frame (4.2.1)
  bool preloadVisible = false;    // and the pages the first frame needs (4.2.1)
  int needScaleLog2 = 0;          // needbuffer at 1/2^k of the screen per axis, jittered
  bool asyncReadback = false;     // the analysis sees the previous frame's needbuffer
  bool trilinearParents = false;  // the parent of a needed page counts as needed too: trilinear
                                  // filtering reads it (runtime/virtual_texture_runtime.h)
  uint32_t seed = 0;  // of the `random` factor: runs differing only in it are independent draws
  // JSON "selection"; the ceiling needs a budget in pages and no latency (it picks for the next
  // frame), and tries at most ceilingCandidates pages a frame (JSON "ceiling_candidates").
  PageSelection selection = PageSelection::kHeuristic;
  uint32_t ceilingCandidates = 32;

  std::string label() const;  // the name, or a short description of the settings
  nlohmann::json toJson() const;
  // Throws std::invalid_argument naming the key and what is wrong.
  static FlightConfiguration fromJson(const nlohmann::json& object,
                                      const FlightConfiguration& defaults);
};

// The side N of the cache's N x N frames for a texture of `description` under `configuration`:
// cacheFrames, or the largest N whose frames hold at most cacheBytes of stored pages, at least 1
// and at most 256 frames and kMaxCacheSideTexels texels per side (one cache texture: a cache of
// more bytes is cut to the largest that texture holds).
uint32_t cacheFramesFor(const FlightConfiguration& configuration,
                        const TextureDescription& description);

// How the LookAhead camera's pages join the requests (FlightConfiguration::lookAheadPrefetch).
inline constexpr EnumNames<bool, 2> kLookAheadPagesNames = {{{false, "merged"}, {true, "prefetch"}}};

// How the analysis reads the needbuffer back: the frame's own (sync), or the previous frame's.
inline constexpr EnumNames<bool, 2> kReadbackNames = {{{false, "sync"}, {true, "async"}}};

}  // namespace vt
