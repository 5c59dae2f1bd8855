#include "verify/flight_capture.h"

#include <cstdio>

#include "verify/oracle_conversions.h"
#include "vt/oracle/capture.h"

namespace vt {

void writeFlightCapture(const std::filesystem::path& folder, const FlightCaptureView& view,
                        const VirtualTextureReader& reader, const RenderSettings& settings,
                        const std::string& renderer, const std::string& fingerprint) {
  oracle::Capture capture;
  capture.renderer = renderer;
  capture.fingerprint = fingerprint;
  capture.texture = reader.path();
  capture.textureIdentity = reader.identity();
  capture.scene = oracle::publicScene(view.mesh, settings.viewport);

  capture.cache = publicCacheState(view.runtime.cacheState());  // as the frame was drawn

  const oracle::RenderOptions options = publicRenderOptions(settings);
  capture.needEncoding = options.needEncoding;
  capture.filtering = options.filtering;
  capture.sampling = options.sampling;
  capture.color.assign(view.color.begin(), view.color.end());
  capture.need = oracle::flatNeed(view.need);

  char name[32];
  std::snprintf(name, sizeof name, "frame%04d.json", view.frame);
  oracle::writeCapture(folder / name, capture);
}

}  // namespace vt
