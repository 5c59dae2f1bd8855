#include "backends/backend.h"

#include <stdexcept>

#include "gl/gl_frame_renderer.h"
#include "gl/headless_context.h"
#include "reference/oracle_frame_renderer.h"
#include "reference/oracle_roles.h"
#include "render/arithmetic_points.h"

namespace vt {

Backend parseBackend(const std::string& name) {
  if (name == "oracle") return Backend::kOracle;
  if (name == "gl") return Backend::kGl;
  throw std::invalid_argument("backend '" + name + "' is not one of oracle, gl");
}

std::string toString(Backend backend) { return backend == Backend::kGl ? "gl" : "oracle"; }

BackendContext::BackendContext(Backend backend)
    : gl_(backend == Backend::kGl ? std::make_unique<HeadlessContext>() : nullptr) {}

BackendContext::~BackendContext() = default;

std::string BackendContext::renderer() const { return gl_ ? gl_->renderer() : kOracleRenderer; }

std::string BackendContext::version() const { return gl_ ? gl_->version() : ""; }

std::string BackendContext::captureName(const RenderSettings& settings) const {
  return gl_ ? gl_->renderer()
             : std::string(kOracleRenderer) + " (" + arithmeticLabel(settings.arithmetic) + ")";
}

std::unique_ptr<FrameRenderer> makeFrameRenderer(Backend backend, const CacheState& cache) {
  if (backend == Backend::kGl) return std::make_unique<GlFrameRenderer>(cache);
  return std::make_unique<reference::OracleFrameRenderer>(cache);
}

bool drawsEveryPage(Backend backend) { return backend == Backend::kOracle; }

std::unique_ptr<FrameRenderer> makeFrameRendererOfEveryPage(Backend backend,
                                                            const VirtualTextureReader& reader,
                                                            const CacheState& fitting) {
  if (drawsEveryPage(backend) && fitting.residentPages.size() < reader.storedPageCount())
    return std::make_unique<reference::OracleFrameRenderer>(reader);
  return makeFrameRenderer(backend, fitting);
}

std::unique_ptr<ResidentRenderer> makeResidentRenderer(const VirtualTextureReader& reader) {
  return std::make_unique<reference::OracleResidentRenderer>(reader);
}

std::unique_ptr<CacheRenderer> makeCacheRenderer() {
  return std::make_unique<reference::OracleCacheRenderer>();
}

}  // namespace vt
