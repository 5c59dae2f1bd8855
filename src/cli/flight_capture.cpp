#include "cli/flight_capture.h"

#include <cstdio>

#include "vt/oracle/capture.h"

namespace vt {

void writeFlightCapture(const std::filesystem::path& folder, const FlightCaptureView& view,
                        const VirtualTextureReader& reader,
                        const reference::RenderSettings& settings, const std::string& renderer) {
  oracle::Capture capture;
  capture.renderer = renderer;
  capture.texture = reader.path();
  capture.textureIdentity = reader.identity();
  capture.scene.viewport = {settings.viewport.width, settings.viewport.height};
  capture.scene.vertices.reserve(view.mesh.vertices.size());
  for (const ClipVertex& v : view.mesh.vertices)
    capture.scene.vertices.push_back(
        {v.position.x, v.position.y, v.position.z, v.position.w, v.uv.x, v.uv.y});
  capture.scene.indices = view.mesh.indices;

  // The cache state as the runtime holds it: each resident page in its frame.
  const PageCache& cache = view.runtime.pageCache();
  capture.cache.allResident = false;
  capture.cache.framesX = cache.framesX();
  capture.cache.framesY = cache.framesY();
  for (const uint64_t index : cache.residentPages()) {
    const PageId page = fromAbsoluteIndex(index);
    const FrameId frame = *cache.frameOf(index);
    capture.cache.pages.push_back({page.level, page.x, page.y, frame.x, frame.y});
  }

  capture.needEncoding =
      settings.need8 ? oracle::NeedEncoding::k8Bit : oracle::NeedEncoding::k32Bit;
  capture.filtering =
      settings.trilinear ? oracle::Filtering::kTrilinear : oracle::Filtering::kBilinear;
  capture.sampling =
      settings.exactFilter ? oracle::Sampling::kTexelFetch : oracle::Sampling::kHardwareLinear;
  capture.color.assign(view.color.begin(), view.color.end());
  capture.need.reserve(view.need.size() * 4);
  for (const glm::uvec4& v : view.need)
    capture.need.insert(capture.need.end(), {v.x, v.y, v.z, v.w});

  char name[32];
  std::snprintf(name, sizeof name, "frame%04d.json", view.frame);
  oracle::writeCapture(folder / name, capture);
}

}  // namespace vt
