#pragma once
// A camera path flown on this machine's GL with the runtime streaming pages into the GL cache
// (`vt-capture flight`, the kit's flight on a GPU runner): each frame drawn from the runtime's
// cache state, its needbuffer analysed under the heuristic, the budget's pages read from the file
// and applied to the cache, which the renderer uploads again (blocks as they are stored for BC1 and
// BC3 textures, the indirection table beside them). With asynchronous readback the needbuffer
// analysed is the previous frame's, as in a game engine. Every n-th frame is drawn again
// synchronously from the cache state it was drawn with and written as a capture
// (capture/capture_writer.h), which `vt crosscheck --captures` judges. What `vt fly --backend gl
// --capture` does, built from the drawing parts and the runtime alone.

#include <cstdint>
#include <filesystem>
#include <string>

#include "format/virtual_texture_reader.h"
#include "render/render_settings.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt::capture {

struct StreamedFlightOptions {
  Viewport viewport{320, 200};
  std::string heuristic = "pixelsum";  // runtime/heuristic.h
  uint32_t budget = 8;                 // pages a frame
  uint32_t cacheFrames = 16;           // the cache holds N x N page frames
  uint32_t initialLevels = 3;          // levels 0 .. K-1 resident before the first frame
  int every = 25;                      // capture frames 0, every, 2 every, ...
  bool asyncReadback = false;
  // Texel fetches with manual trilinear filtering into a 32-bit needbuffer, or the sampler's
  // GL_LINEAR into an 8-bit needbuffer (render/check_modes.h).
  bool linear = false;
  std::string textureName;  // the texture as the manifests name it; empty: its absolute path
};

struct StreamedFlight {
  int frames = 0, captures = 0;
  uint64_t streamed = 0, evicted = 0, misses = 0;
};

// Flies `path` on the current GL context and writes the captures into `folder` (which exists),
// with flight.summary (JSON: the options, per frame the pages streamed, and the totals; not named
// .json, which would read as a capture). Throws InputError
// for a heuristic or a cache the texture cannot have.
StreamedFlight flyAndCapture(const VirtualTextureReader& reader, const Mesh& mesh,
                             const CameraPath& path, const StreamedFlightOptions& options,
                             const std::string& renderer, const std::filesystem::path& folder);

}  // namespace vt::capture
