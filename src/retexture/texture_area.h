#pragma once
// The result of retexturing (thesis 3.3.2): every face of a TexturedScene gets an area of one
// square virtual texture, filled with texels of its source texture, and new texture coordinates
// inside that area.
//
// Texel space of a face: u = s * w, v = t * h for its source texture of w x h texels, with the
// repetitions unrolled (u may leave [0, w)). An area copies the source texels u in
// [sourceX, sourceX + width), v in [sourceY, sourceY + height) (taken modulo the image size) to
// the virtual texture's texels [x, x + width) x [y, y + height), so a face's new coordinates are
//   s' = (s * w + shiftX - sourceX + x) / side,   t' = (t * h + shiftY - sourceY + y) / side
// with the face's shift (faceShift: whole repetitions, zero unless faces were joined)
// (the thesis's s' = (s * w_i + x) / w_d, with the area starting at sourceX instead of 0).

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scene/textured_scene.h"

namespace vt {

struct TextureArea {
  uint32_t texture = 0;              // source texture, index into TexturedScene::textures
  int64_t sourceX = 0, sourceY = 0;  // first source texel copied, unrolled texel space
  uint64_t x = 0, y = 0;             // first virtual-texture texel, finest level
  uint32_t width = 0, height = 0;    // texels
};

struct Retexturing {
  std::string method;  // "baseline" (the thesis's) or "charts" (ours)
  uint32_t pageSize = 0;
  uint64_t side = 0;  // finest level, texels: pageSize * 2^L
  std::vector<TextureArea> areas;
  std::vector<uint32_t> faceArea;  // per face: index into areas
  // Per face: texels added to its unrolled coordinates (u, v) before the area's mapping (whole
  // repetitions of its texture, so the texels are the same); empty means none.
  std::vector<glm::i64vec2> faceShift;
  double seconds = 0.0;  // run time of the layout step
};

// The unrolled texel rectangle a face's coordinates span (not rounded, no shift), [u0, u1] x [v0,
// v1].
struct TexelBounds {
  double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
};

TexelBounds faceTexelBounds(const TexturedScene& scene, const TexturedFace& face);

// The new texture coordinates of every vertex (the formula above, in double, rounded once).
std::vector<glm::vec2> retexturedUvs(const TexturedScene& scene, const Retexturing& layout);

}  // namespace vt
