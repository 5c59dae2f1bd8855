#pragma once
// Triangle setup as a GL rasterizer does it, following what Mesa's llvmpipe computes (DESIGN
// section 7, rules 1 to 5): clipping against the frustum, the window transform, snapping to 1/256
// pixel, the orientation fix, the attribute planes and the integer edge functions.
//
// Window conventions (GL, framebuffer object):
//
//      y ^   pixel (px, py) has its centre at (px + 0.5, py + 0.5); row 0 is at the bottom
//        |   +-----+-----+
//      1 |   | 0,1 | 1,1 |     2x2 quads start at even (px, py): the quad of (3, 2) is
//        |   +-----+-----+     (2, 2) (3, 2) (2, 3) (3, 3)
//      0 |   | 0,0 | 1,0 |
//        |   +-----+-----+
//        +---------------> x
//
// Snapped coordinates are (X - 0.5) * 256 rounded half to even, so pixel centres lie on multiples
// of 256. A centre exactly on an edge belongs to the triangle when the edge is a left or bottom
// edge (the tie rule of rule 4), so a mesh that shares edges covers every pixel once.

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "scene/clip_space_mesh.h"

namespace vt::reference {

// a(px, py) = a0 + dadx * px + dady * py, at the centre of pixel (px, py) (rule 3).
struct Plane {
  float dadx = 0.0f, dady = 0.0f, a0 = 0.0f;
};

// Rule 6: a plane at integer pixel coordinates, fused (llvmpipe on an FMA CPU) or not.
inline float evaluatePlane(const Plane& plane, int px, int py, bool fused) {
  const float x = static_cast<float>(px), y = static_cast<float>(py);
  return fused ? std::fma(plane.dady, y, std::fma(plane.dadx, x, plane.a0))
               : plane.dady * y + (plane.dadx * x + plane.a0);
}

// Edge function of rule 4: covered when c + 256 * (b * py - a * px) > 0 for all three edges.
struct Edge {
  int64_t a = 0, b = 0, c = 0;
  int64_t at(int64_t px, int64_t py) const { return c + 256 * (b * py - a * px); }
};

// A corner of a set-up triangle before snapping: window position, window z, 1/w and the
// perspective attributes s/w and t/w. The result sets (result_set.h) interpolate from these.
struct WindowCorner {
  float x = 0, y = 0, z = 0, oow = 0, sw = 0, tw = 0;
};

// One triangle as the rasterizer sees it: after clipping (a clipped triangle becomes a fan of
// several), oriented, with its planes.
struct SetupTriangle {
  uint32_t primitive = 0;  // index of the mesh triangle (draw order)
  uint32_t fanIndex = 0;   // position in the clipped fan (draw order within the primitive)
  std::array<Edge, 3> edges;
  Plane s, t;                                    // perspective attributes: s/w and t/w
  Plane oneOverW;                                // 1/w
  Plane z;                                       // window z, not perspective-divided
  int minX = 0, minY = 0, maxX = -1, maxY = -1;  // pixels whose centres may be covered
  std::array<WindowCorner, 3> corners;           // in the oriented order of the edges
  // Bit i: the edge opposite corner i lies on the mesh triangle's boundary. Edges between two
  // triangles of a clipped fan are not: the shared-edge rule gives their pixels to one of the two.
  uint8_t outerEdges = 7;

  bool covers(int px, int py) const {
    return edges[0].at(px, py) > 0 && edges[1].at(px, py) > 0 && edges[2].at(px, py) > 0;
  }
};

struct SetupStatistics {
  uint64_t triangles = 0;  // mesh triangles
  uint64_t nonFinite = 0;  // dropped: a NaN or infinite position or clip distance
  uint64_t culled = 0;     // entirely outside one frustum plane
  uint64_t clipped = 0;    // crossed a frustum plane
  uint64_t empty = 0;      // (fan) triangles of zero snapped area or no pixel centre inside
                           // the viewport: they draw nothing
};

// Sets up every triangle of `mesh` for `viewport`. `fused` selects fma (llvmpipe on an FMA CPU)
// or separate multiply and add for the viewport transform of the mesh's vertices (x, y and z);
// vertices made by clipping, and the plane setup itself (rule 3), never fuse.
std::vector<SetupTriangle> setupTriangles(const ClipSpaceMesh& mesh, Viewport viewport, bool fused,
                                          SetupStatistics* statistics = nullptr);

}  // namespace vt::reference
