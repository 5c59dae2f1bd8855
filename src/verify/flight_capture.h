#pragma once
// A flight's frame as a capture of the oracle's format (<vt/oracle/capture.h>), for
// `vt fly --capture DIR`: what the renderer drew, from which clip-space mesh and cache state.

#include <filesystem>
#include <string>

#include "eval/flight.h"
#include "format/virtual_texture_reader.h"
#include "reference/renderer.h"

namespace vt {

// Writes `view` as DIR/frameNNNN.json and its data files; `fingerprint` names the shipped model
// the renderer reproduced (calibrate/fingerprint.h), or is empty.
void writeFlightCapture(const std::filesystem::path& folder, const FlightCaptureView& view,
                        const VirtualTextureReader& reader, const RenderSettings& settings,
                        const std::string& renderer, const std::string& fingerprint = "");

}  // namespace vt
