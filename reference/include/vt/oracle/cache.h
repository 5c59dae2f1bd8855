#pragma once
// A page cache state (thesis 3.1.2, 3.2.2): which pages are resident, in which frames of the
// cache texture. The oracle derives the indirection table from it as a correct renderer must:
// every page's entry names the frame of the page itself or of its nearest resident ancestor. The
// root page (level 0) must be resident.
//
// Frame (fx, fy) holds texels [fx, fx + 1) x [fy, fy + 1) * (P + 2B) of the cache texture, rows
// of rising t. Where a renderer samples the cache with hardware filtering, the frames matter to
// the last bit (the texel coordinates differ), so a capture names them as the engine placed them.

#include <cstdint>
#include <vector>

#include "vt/oracle/export.h"

namespace vt::oracle {

struct ResidentPage {
  uint32_t level = 0, x = 0, y = 0;  // the page (px, py) of level m
  uint32_t frameX = 0, frameY = 0;   // the frame that holds it
};

struct CacheState {
  // Every page resident: each lookup finds the page itself (or, in a sparse texture, its nearest
  // stored ancestor), read straight from the file. Golden images use this state.
  bool allResident = true;
  uint32_t framesX = 0, framesY = 0;  // the cache texture's grid of frames
  std::vector<ResidentPage> pages;    // when not allResident

  static CacheState everything() { return {}; }
};

}  // namespace vt::oracle
