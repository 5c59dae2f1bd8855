#pragma once
// The one place that chooses a renderer (docs/architecture.md, "Renderers to the loop"): the CPU
// oracle (reference/) or the GL path (src/gl/). Everything else draws through FrameRenderer, and
// asks for the roles only the oracle plays through render/reference_roles.h.

#include <memory>
#include <string>

#include "format/virtual_texture_reader.h"
#include "render/frame_renderer.h"
#include "render/precision_model.h"
#include "render/reference_roles.h"
#include "render/render_settings.h"

namespace vt {

class HeadlessContext;

enum class Backend { kOracle, kGl };

// "oracle" or "gl"; throws std::invalid_argument for any other name.
Backend parseBackend(const std::string& name);
std::string toString(Backend backend);

// The oracle's name where a GL implementation names itself (GL_RENDERER).
inline constexpr const char* kOracleRenderer = "vt oracle";

// What drawing with a backend needs on the calling thread while it lasts: for the GL path a
// headless OpenGL 4.5 context (gl/headless_context.h), made current here; for the oracle nothing.
class BackendContext {
 public:
  explicit BackendContext(Backend backend);
  ~BackendContext();
  BackendContext(const BackendContext&) = delete;
  BackendContext& operator=(const BackendContext&) = delete;

  // Who draws: GL_RENDERER and GL_VERSION of the context, or kOracleRenderer and "" for the
  // oracle; messages and reports name the implementation by them.
  std::string renderer() const;
  std::string version() const;
  // The renderer's name for a capture drawn under `settings`: GL_RENDERER, or the oracle's name
  // with its arithmetic ("vt oracle (llvmpipe)"), which picks that model when the capture is
  // judged under auto.
  std::string captureName(const RenderSettings& settings) const;

  // Which backend draws: with a GL context current (kGl) or none (kOracle). What `auto` means
  // for a GL context is resolved above this factory, which links no calibration
  // (workflows/auto_model.h).
  Backend backend() const { return gl_ ? Backend::kGl : Backend::kOracle; }

 private:
  std::unique_ptr<HeadlessContext> gl_;
};

// A renderer that draws from `cache`, which it reads at every draw (so `cache` must outlive it;
// call cacheChanged() after changing it). The GL path needs a current context for its whole life
// (BackendContext, or the caller's own).
std::unique_ptr<FrameRenderer> makeFrameRenderer(Backend backend, const CacheState& cache);

// Whether the backend draws a texture's stored pages without a cache texture (the oracle reads
// them from the file as a frame needs them; the GL path holds what its cache texture holds).
bool drawsEveryPage(Backend backend);

// A renderer of every stored page of `reader` as far as the backend can draw it: `fitting` is the
// cache state of the most pages a cache texture holds (cacheOfLevels). When `fitting` lacks some,
// the oracle draws every page straight from the file instead, and the GL path draws `fitting`
// (FrameRenderer::cache says which). Both must outlive the renderer.
std::unique_ptr<FrameRenderer> makeFrameRendererOfEveryPage(Backend backend,
                                                            const VirtualTextureReader& reader,
                                                            const CacheState& fitting);

// The oracle in its own roles (render/reference_roles.h). `reader` must outlive the renderer.
std::unique_ptr<ResidentRenderer> makeResidentRenderer(const VirtualTextureReader& reader);
std::unique_ptr<CacheRenderer> makeCacheRenderer();

}  // namespace vt
