#pragma once
// Precision models: within which limits a GL implementation may compute differently from the
// oracle's own arithmetic (docs/design.md section 3, "Exactness"). The oracle computes one value
// per pixel with its arithmetic (a point of the space of choices, arithmetic.h) and, under a model
// that leaves any parameter free, the set of every value a conforming implementation could produce
// there (result_set.h). Each parameter says where its value comes from; no width in the oracle is a
// bare number.
//
// Shipped models:
//   llvmpipe  Mesa 22.3 llvmpipe on x86-64 with FMA, every parameter pinned (docs/design.md
//             section 7): every set is one value, the comparison is bit for bit.
//   softpipe  Mesa 22.3 softpipe (reference/softpipe-arithmetic.md, read from its source and
//             confirmed by emulation): every parameter pinned but the denormal mode, which
//             softpipe changes between batches; each set holds the value with denormals flushed
//             and the value with them kept.
//   exact     IEEE float in source order, every parameter pinned: the reference for golden images
//             that no GPU is expected to match bit for bit.
//   gl45      only what the OpenGL 4.5 core and GLSL 4.50 specifications guarantee, and where they
//             are silent the minimum precisions the Khronos conformance tests (dEQP) accept.
// Models measured on one implementation are read from JSON files (precision_model_file.h).

#include <map>
#include <string>
#include <vector>

#include "render/arithmetic.h"

namespace vt {

struct PrecisionModel {
  std::string name;
  std::string renderer;   // the GL_RENDERER a measured model describes; empty for shipped ones
  std::string glVersion;  // the GL_VERSION (driver) it was measured with; empty for shipped ones
  // The oracle's own arithmetic, the centre of every set.
  Arithmetic arithmetic;

  // Rasterization. With the fill rule pinned, coverage is the arithmetic's own, bit for bit, and
  // subpixelBits is its grid; free, vertices may move by 2^-subpixelBits pixel and a centre on an
  // edge may go either way.
  int subpixelBits = 8;
  bool fillRulePinned = true;  // false: a centre on an edge may belong to either triangle
  // Depth: error of the interpolated window z beyond vertex snapping, in units of 2^-23 of the
  // larger of the depth range [0, 1] and the terms its computation sums: those of the window
  // plane's evaluation at the pixel, and those of the corners' window z interpolated to it (a
  // corner clipped from a vertex behind the camera, or a rasterizer's homogeneous barycentrics
  // there, sums terms far beyond the range; reference/triangle_setup.h, WindowCorner::depthTerms).
  // For a triangle inside the depth range the terms lie in [0, 1] and the unit is the range's.
  // With depthRoundsToNearest false, Z24 may store either of the two nearest values.
  double depthUlps = 0;
  bool depthRoundsToNearest = true;

  // Attribute interpolation: error of each interpolated attribute beyond what vertex snapping
  // explains, in units of 2^-23 relative to the size of the terms its float evaluation sums (at
  // least its value; reference/perturbed_triangle.h), 0: the oracle's plane evaluation, bit for
  // bit. `vt calibrate` measures it relative to the value, which is never smaller.
  double attributeUlps = 0;

  // Shader arithmetic of the manual LOD (all `precise`): log2 pinned to the arithmetic's member,
  // or free within log2AbsoluteError and log2Ulps (at least the GLSL 4.50 table's).
  bool log2Pinned = true;
  double log2AbsoluteError = 0;  // bounded: inside [0.5, 2]
  double log2Ulps = 0;           // bounded: outside [0.5, 2]
  double sqrtUlps = 0;           // relative error of sqrt, in units of 2^-23
  double arithmeticUlps = 0;     // of +, -, * in the shader (0: correctly rounded, as the oracle)

  // Texture filtering: the sampler's GL_LINEAR (the hardware_linear sampling mode), pinned to the
  // arithmetic's member or free within subTexelBits and filterErrorUnits. The exact sampling mode
  // fetches texels and filters in the shader's float arithmetic.
  bool filterPinned = true;
  int subTexelBits = 0;         // bounded: texel positions snapped to 2^-subTexelBits texel
  double filterErrorUnits = 0;  // bounded: error of the filtered value, in units of 1/255

  // Framebuffer: a float colour becomes RGBA8 as the arithmetic's colour conversion says (pinned:
  // rounded to nearest, or a measured quantization) or may become either of the two nearest
  // values (GL 4.5 section 2.3.5.2).
  bool colorPinned = true;
  // Denormals in fragment arithmetic: pinned to the arithmetic's choice, or free.
  bool denormalsPinned = true;
  // Block-compressed caches: texels decoded as the arithmetic's block-decoding member (pinned),
  // or each within the least and greatest value of every known member and of the
  // specification's fraction rounded either way (format/block_decoding.h: decodeTexelRange).
  bool decodingPinned = true;

  // Where each parameter's value comes from, by parameter name.
  std::map<std::string, std::string> sources;

  // Every parameter pinned: the oracle reproduces the implementation bit for bit, and each
  // pixel's set is the oracle's one value (but under a measured sqrt table, whose residual
  // against the true sqrt still widens the sets). `auto` fingerprints such a model first.
  bool pinned() const;
  // Every parameter pinned but the denormal mode: each pixel's set is the oracle's value with
  // denormals flushed and its value with them kept (reference/renderer.cpp computes both).
  bool onlyDenormalsFree() const;
  // Coverage is the arithmetic's own (its grid, rounding and tie rule, or its spans).
  bool coveragePinned() const { return fillRulePinned; }
  bool operator==(const PrecisionModel&) const = default;
};

// The model with every parameter pinned to `arithmetic`, named `name`, every parameter's source
// `source`. The shipped pinned models are arithmetic_points.h's.
PrecisionModel pinnedModel(const Arithmetic& arithmetic, const std::string& name,
                           const std::string& source = "pinned to the arithmetic's members");

PrecisionModel gl45Model();

// What `model` allows beyond the specification: each bound wider than gl45's, with the
// parameter's name as in model files and, in words, the value and its specification section.
struct Gl45Excess {
  std::string parameter, text;
};
std::vector<Gl45Excess> excessesOverGl45(const PrecisionModel& model);
// The first excess in words, or "" for a model within gl45.
std::string beyondGl45(const PrecisionModel& model);

}  // namespace vt
