#pragma once
// Which set-up triangle a GL rasterizer shows at each pixel.
//
// Frames are drawn tile by tile: every set-up triangle is binned into the tiles of kTile x kTile
// pixels its box of candidate centres touches (in draw order), and a tile's pixels are decided by
// walking its triangles' boxes inside it, as a tile-binned GL rasterizer does.
//
// Embree supplies the search for single pixels and blocks (the result sets' candidates, tests):
// every set-up triangle is a user primitive whose box, in window coordinates, spans the pixel
// centres its snapped vertices can enclose (an integer range, so the box is exact, not estimated).
// The ray of pixel (px, py) runs along +z through its centre, so it meets the box of every
// triangle that could cover it. Its scene is built on the first such query, so a frame that needs
// none pays nothing for it. A frame whose sets few blocks need (judging a frame that differs at a
// few pixels, RenderSettings::judged) searches the blocks' candidates in the tiles' bins of the
// grown boxes instead (CandidateSearch::kBins), which cost far less to build than Embree's scene
// and find the same candidates (a test).
//
// Either way, for each candidate the GL rules decide exactly, in one function: the integer edge
// functions with the tie rule (coverage), depth from the z plane (rule 7) with the depth format's
// comparison, and GL_LESS against a cleared depth of 1.0, where the earlier drawn triangle wins a
// tie. Embree's own intersection arithmetic never decides. Pixels are queried in coherent packets
// of 4 x 4 rays (rtcIntersect16).

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "reference/triangle_setup.h"
#include "render/render_settings.h"

namespace vt::reference {

// The integer Z24 stores for a window depth z in [0, 1] under `conversion` (render/arithmetic.h):
// z * (2^24 - 1) in float, rounded to nearest even or truncated, as the visibility's depth keys
// store a clamped depth (depthKey in visibility.cpp). A z outside [0, 1] is clamped first (NaN
// gives 0).
uint32_t z24Of(float z, Z24Conversion conversion);

// The winner at one pixel.
struct PixelHit {
  int32_t triangle = -1;  // index into the set-up triangles, -1 for no geometry
  float depth = 1.0f;     // window z of the winner, as stored (Z24: quantized back to float)
  // The nearest depth of another covering triangle that passed the depth test against the clear
  // value (1.0 when none): close to `depth`, the winner is a matter of precision (decals).
  float runnerUpDepth = 1.0f;
};

struct BoxData;

class Visibility {
 public:
  static constexpr int kBlock = 4;  // pixels per side of a packet
  static constexpr int kTile = 16;  // pixels per side of a tile

  // How blockCandidates searches: Embree's packets, or the tiles' bins of the grown boxes (each
  // built by the first query that needs it).
  enum class CandidateSearch { kEmbree, kBins };

  // `margin`: pixels by which each triangle's box of candidate centres grows, for a model under
  // which snapping to a coarser grid may cover centres beside those of the oracle's 8-bit grid.
  Visibility(const std::vector<SetupTriangle>& triangles, Viewport viewport, DepthFormat format,
             const Arithmetic& arithmetic, int margin = 0,
             CandidateSearch search = CandidateSearch::kEmbree);
  ~Visibility();
  Visibility(const Visibility&) = delete;
  Visibility& operator=(const Visibility&) = delete;

  // The pixels of the tile from (x0, y0) (multiples of kTile): hits[dx + kTile dy]; pixels outside
  // the viewport get no hit. Thread-safe.
  void tile(int x0, int y0, std::span<PixelHit, kTile * kTile> hits) const;
  // The triangle shown at pixel (px, py). Thread-safe.
  PixelHit at(int px, int py) const;
  // The 4 x 4 pixels from (x0, y0): hits[dx + 4 dy]; pixels outside the viewport get no hit.
  // Thread-safe.
  std::array<PixelHit, kBlock * kBlock> block(int x0, int y0) const;
  // Every set-up triangle (index) whose box, grown by the margin, holds the centre of (px, py),
  // in draw order. Thread-safe.
  void candidates(int px, int py, std::vector<int32_t>& out) const;
  // The same for the 4 x 4 pixels from (x0, y0), in one packet: every triangle that is some
  // pixel's candidate, in draw order, once each, with the pixels (bit dx + 4 dy) whose candidate
  // it is; pixels outside the viewport have none. Thread-safe.
  struct BlockCandidates {
    std::vector<int32_t> triangles;
    std::vector<uint16_t> pixels;  // per triangle, pixel (dx, dy) of the block as bitOf(dx, dy)
    static uint16_t bitOf(int dx, int dy) {
      return static_cast<uint16_t>(1u << (dx + kBlock * dy));
    }
    // Pixel (dx, dy)'s candidates, in draw order.
    void of(int dx, int dy, std::vector<int32_t>& out) const;
  };
  void blockCandidates(int x0, int y0, BlockCandidates& out) const;

 private:
  const std::vector<SetupTriangle>& triangles_;
  Viewport viewport_;
  DepthFormat format_;
  Arithmetic arithmetic_;
  int margin_;
  // The tiles' triangles: those of tile i are binned_[binStart_[i] .. binStart_[i + 1]), in draw
  // order.
  int tilesX_ = 0;
  std::vector<uint32_t> binStart_, binned_;
  // The same for the boxes grown by the margin and each triangle's candidateMargin
  // (CandidateSearch::kBins), binned by the first query that needs them.
  CandidateSearch search_;
  void binCandidates() const;
  mutable std::once_flag candidatesBinned_;
  mutable std::vector<uint32_t> candidateStart_, candidateBinned_;
  void blockCandidatesFromBins(int x0, int y0, BlockCandidates& out) const;
  // Embree's scene, built by the first query that needs it.
  void buildScene() const;
  std::unique_ptr<BoxData> boxData_;
  mutable std::once_flag built_;
  mutable RTCDevice device_ = nullptr;
  mutable RTCScene scene_ = nullptr;
};

// Window z of a set-up triangle at a pixel centre: offset by + 0.0 and clamped to [0, 1] (rule 7),
// or as interpolated, as the depth member says.
float windowDepth(const SetupTriangle& triangle, int px, int py, const Arithmetic& arithmetic);

}  // namespace vt::reference
