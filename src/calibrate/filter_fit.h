#pragma once
// The GL_LINEAR family of the arithmetic (render/arithmetic.h) fitted from probe draws: samples
// of RGBA8 textures of random texels, clamp to edge, no mipmaps, against every member:
//   - a 16 x 16 texture at 32,768 texel positions, half random on a 2^-12 grid, half on and one
//     float beside 1/256-texel steps (where 8-bit weights round);
//   - a 24 x 40 texture at 16,384 random coordinates of full float precision (the size is no
//     power of two, so u * size - 0.5 rounds, and a fused position shows).
// A member reproduces a sample when every channel is bit for bit the same; the fixed-point
// member's result is a whole number of 1/255, compared as such. When no member does, the filter
// is bounded by the sub-texel grid (4 to 12 bits) whose real-valued bilinear filter leaves the
// smallest largest error, and that error (in units of 1/255).

#include <glm/glm.hpp>

#include "calibrate/family_fit.h"
#include "render/arithmetic.h"

namespace vt::calibrate {

struct FilterFit {
  ParameterFit fit;
  Filter filter;          // the chosen member
  int subTexelBits = 0;   // unpinned only
  double errorUnits = 0;  // unpinned only
};

// Draws the probes on the current GL context. `conversion`: the texel-value member already
// fitted (the float members convert texels with it).
FilterFit fitFilter(UnormConversion conversion);

struct ShaderProbe;
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
