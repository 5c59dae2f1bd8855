#pragma once
// The GL_LINEAR family of the arithmetic (render/arithmetic.h) fitted from probe draws: samples
// of RGBA8 textures of random texels, clamp to edge, no mipmaps, against every member:
//   - a 16 x 16 texture at 32,768 texel positions, half random on a 2^-12 grid, half on and one
//     float beside 1/256-texel steps (where 8-bit weights round);
//   - a 24 x 40 texture at 16,384 random coordinates of full float precision (the size is no
//     power of two, so u * size - 0.5 rounds, and a fused position shows).
//   - where the folder holds it, a group drawn after every other draw: textures of the cache's
//     sizes (drawFilterProbesAtCacheSizes below).
// A member reproduces a sample when every channel is bit for bit the same; the fixed-point
// member's result is a whole number of 1/255, compared as such. When no member does, the filter
// is bounded by the sub-texel grid (4 to 12 bits) whose real-valued bilinear filter leaves the
// smallest largest error, and that error (in units of 1/255).

#include <glm/glm.hpp>

#include "calibrate/family_fit.h"
#include "format/block_decoding.h"
#include "probes/probe_draws.h"
#include "render/arithmetic.h"

namespace vt::calibrate {

// One GL_LINEAR probe draw and what the implementation returned.
struct FilterSample {
  ShaderProbe probe;
  std::vector<glm::vec4> out;
};

// The first pack's two draws (above), on the current GL context or the set drawer.
std::vector<FilterSample> drawFilterProbes();
// The block decoding the fit has found (decoding_fit.h), for textures of blocks.
struct CacheDecoding {
  BlockDecoding decoding;
  bool colourPinned = false, alphaPinned = false;
};
// The filter group, drawn after every draw of the first pack where the drawer holds it
// (probes/probe_draws.h, holdsOptionalGroup): textures of the cache's sizes, 16384 x 2, 2 x 16384
// and 4080 x 4 (30 frames of 136 texels), and a BC1 and a BC3 texture of 4096 x 8 texels of random
// blocks (the compressed cache), each at 4,096 random coordinates of full float precision and
// 4,096 on and beside 1/256-texel steps, where the coordinate's bits and the position's rounding
// show as they do in a cache. Appends them to `samples`, the block textures with their texels
// decoded by `decoding` and only where it is pinned (BC1: colour; BC3: colour and alpha), as
// then the filter alone is measured; false where the folder was drawn before the group.
bool drawFilterProbesAtCacheSizes(std::vector<FilterSample>& samples,
                                  const CacheDecoding& decoding);

struct FilterFit {
  ParameterFit fit;
  Filter filter;          // the chosen member
  int subTexelBits = 0;   // unpinned only
  double errorUnits = 0;  // unpinned only
};

// The family fitted from `samples` (the first pack's, then the group's where drawn).
// `conversion`: the texel-value member already fitted (the float members convert texels with it).
FilterFit fitFilter(const std::vector<FilterSample>& samples, UnormConversion conversion);

// Whether sample i of a GL_LINEAR probe (`probe.inputs[i].xy` the coordinate, `probe.texels` the
// texture) came back as `got` from the member `filter`, converting texels as `conversion` says.
bool reproducesSample(const ShaderProbe& probe, size_t i, const glm::vec4& got,
                      const Filter& filter, UnormConversion conversion);

// The family's members in order, with their names as model files and evidence write them.
struct NamedFilter {
  Filter filter;
  const char* name;
};
const std::vector<NamedFilter>& filterMembers();

}  // namespace vt::calibrate
