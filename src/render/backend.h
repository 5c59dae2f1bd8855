#pragma once
// The one place that chooses a renderer (ARCHITECTURE.md, "Renderers to the loop"): the CPU
// oracle (reference/) or the GL path (src/gl/). Everything else draws through FrameRenderer.

#include <memory>
#include <string>

#include "format/virtual_texture_reader.h"
#include "render/frame_renderer.h"

namespace vt {

class HeadlessContext;

enum class Backend { kOracle, kGl };

// "oracle" or "gl"; throws std::invalid_argument for any other name.
Backend parseBackend(const std::string& name);
std::string toString(Backend backend);

// What drawing with a backend needs on the calling thread while it lasts: for the GL path a
// headless OpenGL 4.5 context (gl/headless_context.h), made current here; for the oracle nothing.
class BackendContext {
 public:
  explicit BackendContext(Backend backend);
  ~BackendContext();
  BackendContext(const BackendContext&) = delete;
  BackendContext& operator=(const BackendContext&) = delete;

 private:
  std::unique_ptr<HeadlessContext> gl_;
};

// A renderer that draws from `cache`, which it reads at every draw (so `cache` must outlive it;
// call cacheChanged() after changing it). The GL path needs a current context for its whole life
// (BackendContext, or the caller's own).
std::unique_ptr<FrameRenderer> makeFrameRenderer(Backend backend, const CacheState& cache);

// A renderer of every stored page of `reader` as far as the backend can draw it: `fitting` is the
// cache state of the most pages a cache texture holds (cacheOfLevels). When `fitting` lacks some,
// the oracle draws every page straight from the file instead, and the GL path draws `fitting`
// (FrameRenderer::cache says which). Both must outlive the renderer.
std::unique_ptr<FrameRenderer> makeFrameRendererOfEveryPage(Backend backend,
                                                            const VirtualTextureReader& reader,
                                                            const CacheState& fitting);

}  // namespace vt
