#pragma once
// The ceiling of page selection (docs/streaming.md, "The ceiling of selection"): a selection that
// may look at what no real strategy can, the next frame's view with every page resident, and so
// says how far choosing pages alone can go at a budget. After each frame it takes the candidates
// a strategy could know of (the pages the frame's requests name, the drawn and the LookAhead
// camera's needed pages, and their missing ancestors) that would change some pixel of the next
// frame (a page between the pixel's resident level and the levels it reads), keeps the few dozen
// that cover the most pixels, and picks greedily, one page at a time, the one whose arrival
// raises the next frame's summed SSIM most, shading only the pixels it changes
// (reference/recolor.h, recolorPixels) and pricing only the windows they touch
// (eval/window_ssim.h). The pages picked go first; the frame's own requests fill what is left of
// the budget (a slot that helps the next frame no further still helps later ones).
//
// With the pool of the next frame (CeilingPool::kNextFrame) the candidates are every page the
// next frame would read better, known or not: that bounds prediction and selection together.
//
// It is greedy and myopic: the best set of pages for the next frame is not always built one best
// page at a time, and a page worth most two frames ahead loses to one worth a little now. So it
// bounds what the strategies it is compared with do, not what any selection could.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "eval/window_ssim.h"
#include "format/virtual_texture_reader.h"
#include "render/cache_state.h"
#include "render/frame.h"
#include "render/render_settings.h"
#include "runtime/page_priority.h"

namespace vt {

struct NextFrameSurvey;  // selection_ceiling.cpp

struct CeilingChoice {
  uint32_t candidates = 0;     // pages tried
  uint32_t picked = 0;         // pages picked for the next frame
  double predictedGain = 0.0;  // of the next frame's mean SSIM, summed over the pages picked
};

enum class CeilingPool { kRequests, kNextFrame };

class CeilingSelection {
 public:
  // `settings`: the evaluation's (the viewport and arithmetic the views are drawn and shaded
  // with). At most `candidates` pages are tried a frame.
  CeilingSelection(const VirtualTextureReader& reader, const RenderSettings& settings,
                   uint32_t candidates = 32, CeilingPool pool = CeilingPool::kRequests);
  ~CeilingSelection();

  // The pages to stream after a frame, most important first: up to `budget` picked for the next
  // frame, then `requests` (the frame's own, most important first) without those. `current`: the
  // cache state the next frame is drawn with unless pages arrive; `next`: the next frame's view
  // drawn with every page resident and the debug channels, its colour the reference.
  std::vector<StreamRequest> choose(const CacheState& current, const Frame& next,
                                    std::span<const StreamRequest> requests, uint32_t budget);

  const CeilingChoice& lastChoice() const { return last_; }

 private:
  struct Candidate;
  // The candidates a frame tries, most pixels first, with their pixels and stored pages.
  std::vector<Candidate> candidatesOf(const CacheState& current, const NextFrameSurvey& survey,
                                      std::span<const StreamRequest> requests) const;
  // What the candidate's arrival, in `frame`, adds to the next frame's summed SSIM.
  double tryCandidate(const Candidate& candidate, const Frame& next, glm::uvec2 frame);
  // Up to `budget` picks, one page at a time, each left resident in the trial cache: the
  // candidate and its gain of the mean SSIM.
  std::vector<std::pair<size_t, double>> pickGreedily(const std::vector<Candidate>& candidates,
                                                      const Frame& next,
                                                      std::span<const glm::uvec2> spare,
                                                      uint32_t budget);
  // Resident in the trial cache at frame `frame`: writes its texels there and points every entry
  // of its subtree that falls back to a coarser level at it. Returns the entries changed, to undo.
  std::vector<std::pair<PageId, glm::u16vec4>> place(const Candidate& candidate, glm::uvec2 frame);
  void undo(const std::vector<std::pair<PageId, glm::u16vec4>>& changed);

  const VirtualTextureReader& reader_;
  RenderSettings settings_;
  uint32_t maxCandidates_;
  CeilingPool pool_;
  std::unique_ptr<CacheState> trial_;  // the current entries, and texels of the frames read
  WindowSsim ssim_;
  std::vector<uint8_t> color_, shaded_;
  CeilingChoice last_;
};

}  // namespace vt
