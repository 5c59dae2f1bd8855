#include "eval/evaluation.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <thread>

#include "backends/backend.h"
#include "common/elapsed_time.h"
#include "common/error.h"
#include "common/parallel_for.h"
#include "common/resource_limits.h"
#include "eval/flight_run.h"
#include "eval/frame_plan.h"
#include "eval/image_metrics.h"
#include "eval/selection_ceiling.h"
#include "runtime/needbuffer_scale.h"

namespace vt {
namespace {

using Clock = std::chrono::steady_clock;

// The needbuffers an evaluation draws besides each view's own, by NeedPass::key (frame_plan.h): a
// camera (the view, or a LookAhead camera) at a needbuffer scale. The view at full scale is the
// shared frame itself.
using PassKey = std::pair<LookAhead, int>;

struct NeedImage {
  std::vector<glm::uvec4> need;
  std::vector<float> depth;
  double seconds = 0.0;
};

// Every camera view of the path, drawn once for all configurations: with every page resident and
// the fragment inputs recorded (the reference image, its needbuffer and depth), and the extra
// needbuffer passes the configurations' frame plans ask for. Needbuffers and depth do not depend on
// the cache state; each configuration's colour is the recorded frame shaded again under its own
// cache state (reference/recolor.h), the same bytes as drawing it.
class SharedViews {
 public:
  SharedViews(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
              const RenderSettings& settings,
              const std::vector<FlightConfiguration>& configurations)
      : mesh_(mesh),
        path_(path),
        configurations_(configurations),
        everything_(makeResidentRenderer(reader)),
        settings_(settings) {
    settings_.needScaleLog2 = 0;
    settings_.debugChannels = true;
  }

  // Draws frame `frameNumber`'s view and the passes of its plans other than the view, each with
  // every thread, each distinct pass once. The view is taken from `drawn` when it holds one
  // (drawView() drew it ahead, in `seconds`).
  void draw(int frameNumber, Frame* drawn = nullptr, double seconds = 0.0) {
    const auto start = Clock::now();
    plans_.clear();
    for (const FlightConfiguration& c : configurations_)
      plans_.push_back(planFrame(c, settings_.viewport, path_, frameNumber));
    if (drawn != nullptr && !drawn->triangle.empty()) {
      std::swap(view_, *drawn);
      drawn->triangle.clear();
      viewSeconds_ = seconds;
    } else {
      drawView(frameNumber, view_);
      viewSeconds_ = secondsSince(start);
    }
    passes_.clear();
    for (const FramePlan& plan : plans_) {
      if (!plan.needPassIsTheView()) drawPass(plan.need);
      if (plan.lookAhead) drawPass(*plan.lookAhead);
    }
  }

  // Frame `frameNumber`'s view alone, with every page resident and the debug channels.
  void drawView(int frameNumber, Frame& out) const {
    everything_->draw(toClipSpace(mesh_, path_.at(frameNumber), settings_.viewport), settings_,
                      out);
  }

  const Frame& view() const { return view_; }
  double viewSeconds() const { return viewSeconds_; }
  // Configuration r's plan of the current frame.
  const FramePlan& plan(size_t r) const { return plans_.at(r); }
  // The pass's needbuffer (and depth) of the current frame.
  const NeedImage& pass(const NeedPass& pass) const { return passes_.at(pass.key()); }
  double totalSeconds() const {
    double seconds = viewSeconds_;
    for (const auto& [key, image] : passes_) seconds += image.seconds;
    return seconds;
  }

 private:
  void drawPass(const NeedPass& pass) {
    if (passes_.contains(pass.key())) return;
    NeedImage& image = passes_[pass.key()];
    const auto passStart = Clock::now();
    RenderSettings settings = settings_;
    settings.debugChannels = false;
    settings.needOnly = true;
    settings.needScaleLog2 = pass.scaleLog2;
    settings.viewport = pass.viewport;
    everything_->draw(toClipSpace(mesh_, pass.view, pass.viewport, pass.jitter), settings,
                      scratch_);
    image.need = std::move(scratch_.need);
    image.depth = std::move(scratch_.depth);
    image.seconds = secondsSince(passStart);
  }

  const Mesh& mesh_;
  const CameraPath& path_;
  const std::vector<FlightConfiguration>& configurations_;
  const std::unique_ptr<const ResidentRenderer> everything_;
  RenderSettings settings_;
  std::vector<FramePlan> plans_;
  Frame view_, scratch_;
  double viewSeconds_ = 0.0;
  std::map<PassKey, NeedImage> passes_;
};

// One configuration's run inside the evaluation: its flight, and its own buffers (the colour of
// each frame, and the previous frame's needbuffer under asynchronous readback).
struct RunState {
  std::unique_ptr<FlightRun> run;
  std::unique_ptr<CeilingSelection> ceiling;  // with the ceiling's selection
  std::vector<uint8_t> color;
  std::vector<glm::uvec4> delayedNeed;
  std::vector<float> delayedDepth;
};

// Frame `f` of one run from the shared views, its colour already shaded under its cache state:
// the needbuffers its configuration reads, then the run's analysis, quality and streaming. Its
// drawing time is the shared passes' it reads: what drawing the frame once costs.
void flyFrame(RunState& state, const SharedViews& views, const FramePlan& plan,
              std::span<const uint8_t> referenceColor, const PreparedReference& reference, int f,
              const Frame* next) {
  double drawSeconds = views.viewSeconds();
  std::span<const glm::uvec4> need = views.view().need;
  std::span<const float> depth = views.view().depth;
  if (!plan.needPassIsTheView()) {
    const NeedImage& reduced = views.pass(plan.need);
    need = reduced.need;
    depth = reduced.depth;
    drawSeconds += reduced.seconds;
  }
  std::span<const glm::uvec4> lookAheadNeed;
  if (plan.lookAhead) {
    const NeedImage& ahead = views.pass(*plan.lookAhead);
    lookAheadNeed = ahead.need;
    drawSeconds += ahead.seconds;
  }
  if (!state.run->runtime().needsDepth()) depth = {};
  std::vector<glm::uvec4> currentNeed;
  std::vector<float> currentDepth;
  if (plan.delayedReadback) {  // the analysis sees the previous frame's needbuffer
    currentNeed.assign(need.begin(), need.end());
    currentDepth.assign(depth.begin(), depth.end());
    std::swap(currentNeed, state.delayedNeed);
    std::swap(currentDepth, state.delayedDepth);
    need = currentNeed;
    depth = currentDepth;
  }
  DrawnFrame drawn{.color = state.color,
                   .need = need,
                   .depth = depth,
                   .lookAheadNeed = lookAheadNeed,
                   .reference = referenceColor,
                   .preparedReference = &reference};
  if (state.ceiling && next != nullptr)
    drawn.select = [&](std::span<const StreamRequest> requests,
                       const VirtualTextureRuntime& runtime) {
      return state.ceiling->choose(runtime.cacheState(), *next, requests,
                                   state.run->configuration().budget);
    };
  state.run->frame(f, plan.previous, plan.camera, drawn, drawSeconds);
}

}  // namespace

void requireEvaluationFits(const std::filesystem::path& origin, const TextureDescription& texture,
                           Viewport screen,
                           const std::vector<FlightConfiguration>& configurations) {
  const uint64_t storedSide = uint64_t{texture.pageSize} + 2 * uint64_t{texture.border};
  // A frame holds its RGBA8 texels and, for a block format, its blocks too.
  const uint64_t frameBytes = storedSide * storedSide * 4 +
                              (isBlockCompressed(texture.format) ? texture.storedPageBytes() : 0);
  uint64_t stateBytes = 0;
  for (const FlightConfiguration& c : configurations) {
    const uint64_t frames = cacheFramesFor(c, texture);
    stateBytes += frames * frames * frameBytes +
                  static_cast<uint64_t>(screen.width) * static_cast<uint64_t>(screen.height) * 4;
  }
  if (stateBytes > kMaxEvaluationStateBytes)
    throw limitError(origin,
                     "flying " + std::to_string(configurations.size()) +
                         " configurations in lockstep (each cache and frame held at once)",
                     stateBytes, kMaxEvaluationStateBytes, " bytes");
}

Evaluation evaluate(const VirtualTextureReader& reader, const Mesh& mesh, const CameraPath& path,
                    const std::vector<FlightConfiguration>& configurations,
                    const EvaluationOptions& options) {
  const auto start = Clock::now();
  const unsigned threads =
      options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  const ThreadLimit parallelism(threads);
  RenderSettings settings = options.settings;
  settings.threads = threads;
  settings.needScaleLog2 = 0;
  const int frames = path.frameCount();
  const uint64_t total = static_cast<uint64_t>(frames) * configurations.size();
  const auto report = [&](uint64_t done) {
    if (options.progress) options.progress(done, total);
  };

  SharedViews views(reader, mesh, path, settings, configurations);
  const std::unique_ptr<const ResidentRenderer> referenceTexture =
      options.reference ? makeResidentRenderer(*options.reference) : nullptr;
  Frame referenceFrame;
  const std::unique_ptr<const CacheRenderer> recolorer = makeCacheRenderer();
  FlightOptions flight;
  flight.settings = settings;
  // The ceiling's runs pick pages with the next frame's view: each view is then drawn a frame
  // ahead (once still).
  flight.drawsNextView = true;
  const bool drawAhead =
      std::any_of(configurations.begin(), configurations.end(), [](const FlightConfiguration& c) {
        return c.selection != PageSelection::kHeuristic;
      });
  Frame next;
  double nextSeconds = 0.0;
  Evaluation evaluation;
  std::vector<RunState> states(configurations.size());
  double sharedSeconds = 0.0;
  for (int f = 0; f < frames; ++f) {
    views.draw(f, &next, nextSeconds);
    sharedSeconds += views.totalSeconds();
    const bool ahead = drawAhead && f + 1 < frames;
    if (ahead) {
      const auto aheadStart = Clock::now();
      views.drawView(f + 1, next);
      nextSeconds = secondsSince(aheadStart);
    }
    if (f == 0)  // the initial cache states need the first view's needbuffer
      for (size_t r = 0; r < configurations.size(); ++r) {
        states[r].run = std::make_unique<FlightRun>(
            reader, configurations[r], flight,
            reducedViewport(settings.viewport, configurations[r].needScaleLog2),
            initialPages(reader, configurations[r], views.view().need, settings.need8));
        if (configurations[r].selection != PageSelection::kHeuristic)
          states[r].ceiling = std::make_unique<CeilingSelection>(
              reader, settings, configurations[r].ceilingCandidates,
              configurations[r].selection == PageSelection::kCeiling ? CeilingPool::kRequests
                                                                     : CeilingPool::kNextFrame);
      }
    const auto recolorStart = Clock::now();
    std::vector<const CacheState*> caches;
    std::vector<std::vector<uint8_t>*> colors;
    for (RunState& state : states) {
      caches.push_back(&state.run->runtime().cacheState());
      colors.push_back(&state.color);
    }
    recolorer->recolor(views.view(), caches, settings, colors);
    evaluation.recolorSeconds += secondsSince(recolorStart);
    std::span<const uint8_t> referenceColor = views.view().color;
    if (referenceTexture) {
      const auto referenceStart = Clock::now();
      RenderSettings colourOnly = settings;
      colourOnly.debugChannels = false;
      referenceTexture->draw(toClipSpace(mesh, path.at(f), settings.viewport), colourOnly,
                             referenceFrame);
      referenceColor = referenceFrame.color;
      evaluation.referenceSeconds += secondsSince(referenceStart);
    }
    const PreparedReference prepared(
        ImageView{settings.viewport.width, settings.viewport.height, referenceColor});
    if (referenceTexture)
      evaluation.encoding.push_back(prepared.compare(
          ImageView{settings.viewport.width, settings.viewport.height, views.view().color}));
    parallelFor(states.size(), threads, [&](size_t r) {
      flyFrame(states[r], views, views.plan(r), referenceColor, prepared, f,
               ahead ? &next : nullptr);
    });
    report(static_cast<uint64_t>(f + 1) * configurations.size());
  }
  for (size_t r = 0; r < configurations.size(); ++r)
    evaluation.runs.push_back({configurations[r], states[r].run->finish(),
                               cacheFramesFor(configurations[r], reader.description())});
  evaluation.viewSeconds = sharedSeconds;
  evaluation.wallSeconds = secondsSince(start);
  return evaluation;
}

void requireSamePages(const VirtualTextureReader& flown, const VirtualTextureReader& reference) {
  const TextureDescription &a = flown.description(), &b = reference.description();
  if (a.pageSize != b.pageSize || a.border != b.border || a.levelCount != b.levelCount)
    throw InputError(reference.path(),
                     "pages of " + std::to_string(b.pageSize) + " texels, border " +
                         std::to_string(b.border) + ", " + std::to_string(b.levelCount) +
                         " levels: not the pages of " + flown.path().string() + " (" +
                         std::to_string(a.pageSize) + ", border " + std::to_string(a.border) +
                         ", " + std::to_string(a.levelCount) + " levels)");
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
