#pragma once
// `vt inspect`'s work as one call: one flight of a configuration, and a self-contained HTML page
// (eval/inspect_page.h) to step through a range of its frames: per frame the rendered image, the
// reference (every needed page resident), their difference, the needbuffer by level, the level
// each needed page resolves to, the cache atlas, the statistics, the head of the priority queue
// with each page's heuristic terms, and the pages streamed for the next frame.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "eval/flight_configuration.h"
#include "format/virtual_texture_reader.h"
#include "scene/camera_path.h"
#include "scene/clip_space_mesh.h"
#include "scene/mesh.h"

namespace vt {

struct Inspection {
  std::string texture, sceneName;  // as given, for the page's settings
  std::filesystem::path pathFile;  // empty: the box room's turn
  Mesh mesh;
  CameraPath path;
  FlightConfiguration configuration;
  // A second configuration flown over the same path and shown beside the first: each one's
  // frames, differences against the reference, resident levels, statistics and queue, and
  // where each is nearer the reference.
  std::optional<FlightConfiguration> against;
  Viewport screen{320, 200};
  std::string screenText;               // as given
  int first = 0, last = -1, every = 1;  // the frames shown (last -1: the path's last)
  int queue = 24;                       // entries of the priority queue shown per frame
  int atlasSide = 512;                  // the cache atlas image's largest side
  std::filesystem::path output;         // the HTML file
};

// Throws std::invalid_argument for frames outside the path or more than a page holds.
void inspectToPage(const VirtualTextureReader& reader, const Inspection& request,
                   std::ostream& out);

}  // namespace vt
