#pragma once
// Which set-up triangle a GL rasterizer shows at each pixel, found with Embree.
//
// Embree supplies the search: every set-up triangle is a user primitive whose box, in clip
// coordinates (x, y, w), is its clipped triangle's box widened by 1/32 pixel at its largest w,
// far more than snapping (1/512 pixel) and float rounding move an edge. The ray of pixel (px, py)
// runs from the origin along (x_ndc, y_ndc, 1), so it meets the box of every triangle whose
// snapped shape could contain the pixel's centre. For each such candidate the GL rules decide
// exactly: the integer edge functions with the tie rule (coverage), depth from the z plane
// (rule 7) with the depth format's comparison, and GL_LESS against a cleared depth of 1.0, where
// the earlier drawn triangle wins a tie. Embree's own intersection arithmetic never decides.

#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "reference/triangle_setup.h"

namespace vt::reference {

enum class DepthFormat { kDepth24, kDepth32F };

// The winner at one pixel.
struct PixelHit {
  int32_t triangle = -1;  // index into the set-up triangles, -1 for no geometry
  float depth = 1.0f;     // window z of the winner, as stored (Z24: quantized back to float)
  // The nearest depth of another covering triangle that passed the depth test against the clear
  // value (1.0 when none): close to `depth`, the winner is a matter of precision (decals).
  float runnerUpDepth = 1.0f;
};

class Visibility {
 public:
  Visibility(const std::vector<SetupTriangle>& triangles, Viewport viewport, DepthFormat format,
             bool fused);
  ~Visibility();
  Visibility(const Visibility&) = delete;
  Visibility& operator=(const Visibility&) = delete;

  // The triangle shown at pixel (px, py). Thread-safe.
  PixelHit at(int px, int py) const;

  // What Embree's callbacks see of the scene.
  struct SceneData {
    const std::vector<SetupTriangle>* triangles;
    float marginPerW[2];  // 1/32 pixel in clip x and y units, per unit of w
  };

 private:
  SceneData data_;
  Viewport viewport_;
  DepthFormat format_;
  bool fused_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// Window z of a set-up triangle at a pixel centre, clamped to [0, 1] (rule 7).
float windowDepth(const SetupTriangle& triangle, int px, int py, bool fused);

}  // namespace vt::reference
