#pragma once
// `vt build` (thesis 3.3.1, "vtmtc"): compiles a layout into a virtual-texture file, out of core.
//
// The finest level is produced one texel row at a time from the images (image_rows.h); every
// level keeps only a ring of its most recent rows (row_ring.h); each pair of rows of level m
// (more for wider filters) makes the next row of level m - 1 at once (mip_kernel.h), and as soon
// as a level holds all rows of a page row and its borders, those pages are cut, their NoiseValues
// computed, and written at their place in the file, in parallel. No level is ever whole in memory.
//
// Memory bound: each level's ring holds C = P + 2 B' + 2 + 2 r rows, where B' = max(B, 2 + r)
// and r is the filter's reach (0 box, 1 tent), but only in strips of 256 columns that an image
// influenced within the last C rows (row_ring.h): at most, per level, the largest number of
// strips the footprints of the images near one row cover, times C * 256 * c bytes, never more
// than C rows of side_m * c bytes; plus a column table of side_m / 64 bytes per level, one page
// per thread, one scanline per open image, and each image of region placements whole while rows
// pass its placements (build/image_rows.h). ringBytesBound computes it from the layout. For
// 16384^2 RGB texels covered by images, P = 128, B = 4, box: under 14 MB; one 1 x 1 image placed
// near column 2^22: one strip per level, about 2 MB in all.

#include <cstdint>
#include <filesystem>

#include "build/layout.h"

namespace vt {

struct BuildOptions {
  unsigned threads = 0;        // 0: every core
  bool progress = true;        // a progress bar, when stderr is a terminal
  uint64_t keepFreeBytes = 0;  // disk space that must stay free after the build
  // Measure each page's error through every ancestor (build/ancestor_error.h) once the pages are
  // written, reading them back, and store the table after them (file version 3).
  bool ancestorErrors = false;
};

struct BuildReport {
  uint64_t storedPages = 0;
  uint64_t totalPages = 0;
  uint64_t fileBytes = 0;
  uint64_t ringBytes = 0;      // rows held by all levels, the bulk of the builder's memory
  uint64_t scanlineBytes = 0;  // most image bytes held at once (scanlines and decoded images)
  double seconds = 0.0;
  double ancestorErrorSeconds = 0.0;  // of `seconds`, measuring the ancestor errors
};

// The bound of the documented formula above for the rings, in bytes.
uint64_t ringBytesBound(const Layout& layout);

// Builds `output` from a validated layout. Checks first the rings' memory (at most
// kMaxBuildRingBytes, common/resource_limits.h), the stored pages and the free disk space; writes
// a temporary file renamed at the end. The bytes written do not depend on the thread count.
BuildReport buildVirtualTexture(const Layout& layout, const std::filesystem::path& output,
                                const BuildOptions& options = {});

}  // namespace vt
