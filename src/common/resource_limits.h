#pragma once
// What an input may ask for. A size read from a file (a header field, a layout entry, a map's
// surfaces, a camera path's frames, an archive entry) that would need more memory, disk or time
// than any real input needs is refused before anything is allocated for it, with one line naming
// the file, what was asked and the limit:
//   "scene.vt: header field stored_page_count asks for 1431655765 pages, the limit is 268435456
//   pages"
// Each limit lies far above what the real inputs of this project use (next to each: the largest
// we know) and far below what would exhaust a machine.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

#include "common/error.h"

namespace vt {

// Pages one virtual texture may store: 2^28 pages of 128^2 RGBA texels are about 19 TiB, and the
// reader's tables for them 5 GiB. (A 16384^2 texture with P = 128 stores 21,845.)
inline constexpr uint64_t kMaxStoredPages = uint64_t{1} << 28;

// Bytes `vt build` may hold in its row rings (texture_builder.h gives the bound): 16 GiB. A
// 2^20-texel-wide RGBA texture with P = 128 needs 1.2 GB; 16384^2 RGB needs 14 MB.
inline constexpr uint64_t kMaxBuildRingBytes = uint64_t{16} << 30;

// Bytes of one image that `vt build` decodes whole (region placements, layout.h): 4 GiB, an RGBA
// image of 32768^2. (Whole-image placements are streamed by scanlines and need no such limit.)
inline constexpr uint64_t kMaxWholeImageBytes = uint64_t{4} << 30;

// Vertices and indices a Quake 3 map's drawn surfaces may give after patch tessellation: 2^24 and
// 2^26. Surfaces may share vertex ranges, so a small file could otherwise ask for billions.
// (q3dm6ish gives 4,406 vertices.)
inline constexpr uint64_t kMaxMapVertices = uint64_t{1} << 24;
inline constexpr uint64_t kMaxMapIndices = uint64_t{1} << 26;

// Texel rows `vt retexture` walks to count the texels a layout's triangles reference
// (layout_quality.h): each triangle's rows in its area, 2^27. The OpenArena maps need at most
// 9.0 million (suspended; q3dm6ish 0.9 million). A triangle spans as many rows as its texture
// has texels along its coordinates' range, so an image header claiming 65535^2 texels gives 65535
// rows to each triangle of a face that spans the image once, and repeated coordinates multiply
// that.
inline constexpr uint64_t kMaxCoverageRows = uint64_t{1} << 27;

// Pairs of faces that share a vertex position, counted at each position they share, that
// `vt retexture` tries to join into charts (face_charts.h): 2^22; and the vertices it checks for
// them (each pair's second face's indices): 2^26. The OpenArena maps need at most 50,306 pairs and
// 268,155 vertices (czest2ctf; q3dm6ish 5,536 and 26,853). Every two faces meeting at a position
// form a pair, so faces that share their vertices many times over would give pairs by the square
// of their number.
inline constexpr uint64_t kMaxChartPairs = uint64_t{1} << 22;
inline constexpr uint64_t kMaxChartVertexChecks = uint64_t{1} << 26;

// Bytes one file of a .pk3 archive may inflate to: 256 MiB (the largest file of OpenArena's
// archives is a 10.2 MB map). A zip entry may claim, or inflate to, far more than its compressed
// size.
inline constexpr uint64_t kMaxPackageEntryBytes = uint64_t{256} << 20;

// Bytes of one shader script of a .pk3 archive: 4 MiB (OpenArena's largest script is far below
// 1 MB). Every script of the packages is tokenised, so a script inflated from a small archive
// could otherwise cost seconds and memory out of all proportion to the map.
inline constexpr uint64_t kMaxShaderScriptBytes = uint64_t{4} << 20;

// Frames of a camera path: 10^6, more than four hours at 60 frames a second. Every frame is
// rendered, so a path of 2^31 frames would run for years.
inline constexpr int64_t kMaxCameraPathFrames = 1'000'000;

// Bytes `vt eval` holds for its runs at once: they fly in lockstep, each with its page cache
// (cache_frames^2 frames of (P + 2B)^2 RGBA8 texels) and a colour buffer of the screen: 8 GiB, the
// reproduction's memory target. A cache texture is reserved whole but written only where pages
// land (common/zeroed_buffer.h), so this bounds what the runs could come to hold, not what a short
// flight touches. (Chapter 4's 31 indoor configurations at 1024 x 768 with caches of 48 x 48
// frames of 136^2 texels count 5.4 GB; a configurations file of 1,000 caches of 256 x 256 frames
// would ask for 4.8 TB.)
inline constexpr uint64_t kMaxEvaluationStateBytes = uint64_t{8} << 30;

// Pixels a command may draw along a camera path: its frames x the viewport's pixels x the passes
// over the path (a flight with --quality also draws each frame's reference image; `vt eval` draws
// the reference and every configuration; `vt golden` its frames once): 2^35, checked before the
// first frame. The longest run of this project's own, chapter 4's indoor evaluation of
// am_thornish at the thesis's 1280 x 800 (24 passes over 723 frames), draws 1.8 * 10^10 pixels;
// at 320 x 200, as reproduced here, 1.1 * 10^9. A path of 10^6 frames (kMaxCameraPathFrames) at
// 320 x 200 would draw 6.4 * 10^10 pixels, days of the oracle's time.
inline constexpr uint64_t kMaxPathPixels = uint64_t{1} << 35;
// What a frame costs besides its pixels (needbuffer analysis, streaming, records), in pixels:
// every frame counts as at least 4,096. Measured with `vt fly` of q3dm6ish's storyboard (375
// frames): 16 x 16 takes about 1 ms a frame beyond the start, 320 x 200 about 24 ms, so 1 ms is
// about 2,700 pixels' work. Without it, 10^6 frames of 16 x 16 would pass as 2.6 * 10^8 pixels.
inline constexpr uint64_t kFrameFixedPixels = 4096;

// Texels per side of a page cache texture, and pixels per side of a captured frame: 16384, the
// GL_MAX_TEXTURE_SIZE of llvmpipe and of current GPUs. (The flights' default cache, 16 x 16 frames
// of 136 texels, is 2,176 texels wide.)
inline constexpr uint64_t kMaxCacheSideTexels = 16384;
inline constexpr uint64_t kMaxViewportSide = 16384;

// Entries of a texture's page table and indirection table: one for every page of every level,
// (4^L - 1) / 3 for L levels (thesis 3.1.1.1), however few pages the file stores, as the
// indirection texture the shader reads is dense. 2^27 entries allow L = 14 (89,478,485 entries,
// 8192^2 pages on the finest level; a 16384^2 texture with P = 128 has L = 8). The runtime keeps
// 17 bytes per entry (table, residency, indirection copy), the oracle's cache state 16.
inline constexpr uint64_t kMaxPageTableEntries = uint64_t{1} << 27;
inline constexpr uint64_t kPageTableBytesPerEntry = 17;

// The error for a request beyond a limit: "<file>: <what> asks for <asked><unit>, the limit is
// <limit><unit>", e.g. what = "header field stored_page_count", unit = " pages".
inline InputError limitError(const std::filesystem::path& file, const std::string& what,
                             uint64_t asked, uint64_t limit, const std::string& unit) {
  return InputError(file, what + " asks for " + std::to_string(asked) + unit + ", the limit is " +
                              std::to_string(limit) + unit);
}

// `levelCount` after checking that the page tables of a texture of that many levels stay within
// kMaxPageTableEntries; before they are allocated, by every user of them (the runtime, the
// oracle's cache state). Throws limitError naming `file` and the bytes the tables would need.
inline uint32_t requirePageTablesFit(const std::filesystem::path& file, uint32_t levelCount) {
  const uint64_t entries = levelCount >= 32
                               ? UINT64_MAX / kPageTableBytesPerEntry
                               : ((uint64_t{1} << (2 * levelCount)) - 1) / 3;  // thesis 3.1.1.1
  if (entries > kMaxPageTableEntries)
    throw limitError(file,
                     "building the page tables of " + std::to_string(levelCount) +
                         " levels (an entry for " + "each of the " + std::to_string(entries) +
                         " pages, stored or not)",
                     entries * kPageTableBytesPerEntry,
                     kMaxPageTableEntries * kPageTableBytesPerEntry, " bytes");
  return levelCount;
}

// Checks, before the first frame is drawn, that `passes` runs over the `frames` frames of the
// camera path `file` at width x height pixels stay within kMaxPathPixels; throws limitError
// naming the path and the pixels they would draw otherwise.
inline void requirePathPixelsFit(const std::filesystem::path& file, uint64_t frames, uint64_t width,
                                 uint64_t height, uint64_t passes) {
  const bool floored = width * height < kFrameFixedPixels;  // each below 2^14: no overflow
  const uint64_t perPass = frames * std::max(width * height, kFrameFixedPixels);  // below 2^48
  const uint64_t pixels =
      passes > UINT64_MAX / std::max<uint64_t>(perPass, 1) ? UINT64_MAX : perPass * passes;
  if (pixels > kMaxPathPixels)
    throw limitError(file,
                     "drawing its " + std::to_string(frames) + " frames at " +
                         std::to_string(width) + " x " + std::to_string(height) + " " +
                         std::to_string(passes) + (passes == 1 ? " time" : " times") +
                         (floored ? " (a frame counts as at least " +
                                        std::to_string(kFrameFixedPixels) + " pixels)"
                                  : std::string()),
                     pixels, kMaxPathPixels, " pixels");
}

}  // namespace vt
