#pragma once
// Precision models: within which limits a GL implementation may compute differently from the
// oracle's own arithmetic (DESIGN section 3, "Exactness"). The oracle computes one value per pixel
// with its arithmetic (`exact` IEEE float, or llvmpipe's measured arithmetic, precision_profile.h)
// and, under a model that leaves any parameter free, the set of every value a conforming
// implementation could produce there (result_set.h). Each parameter says where its value comes
// from; no width in the oracle is a bare number.
//
// Shipped models:
//   llvmpipe  Mesa 22.3 llvmpipe on x86-64 with FMA, every parameter pinned (DESIGN section 7):
//             every set is one value, the comparison is bit for bit.
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

#include "render/precision_profile.h"

namespace vt {

// How a sampler's GL_LINEAR weights the four texels.
enum class FilterArithmetic {
  kLlvmpipe8Bit,  // pinned: rule 9 of DESIGN section 7 (8-bit weights, fixed-point lerps)
  kFloat,         // pinned: IEEE float positions, weights and lerps
  kBounded,       // free within subTexelBits and filterErrorUnits
};

// The shader's log2 (the manual LOD).
enum class Log2Arithmetic {
  kLlvmpipe,  // pinned: llvmpipe's polynomial (rule 8)
  kSoftpipe,  // pinned: logf(x) * 1.442695f (reference/softpipe-arithmetic.md, 5.2)
  kIeee,      // pinned: the C library's log2f, correctly rounded on this project's machines
  kBounded,   // free within the GLSL 4.50 precision table (log2AbsoluteError, log2Ulps)
};

struct PrecisionModel {
  std::string name;
  std::string renderer;   // the GL_RENDERER a measured model describes; empty for shipped ones
  std::string glVersion;  // the GL_VERSION (driver) it was measured with; empty for shipped ones
  // The oracle's own arithmetic, the centre of every set.
  PrecisionProfile arithmetic = PrecisionProfile::kExact;

  // Rasterization. Vertices are snapped to 2^-subpixelBits pixel; with 8 bits and a pinned fill
  // rule coverage is the oracle's (rule 4), bit for bit.
  int subpixelBits = 8;
  bool fillRulePinned = true;  // false: a centre on an edge may belong to either triangle
  // Depth: relative error of the interpolated window z beyond vertex snapping, in units of 2^-23;
  // with depthRoundsToNearest false, Z24 may store either of the two nearest values.
  double depthUlps = 0;
  bool depthRoundsToNearest = true;

  // Attribute interpolation: relative error of each interpolated attribute beyond what vertex
  // snapping explains, in units of 2^-23 (0: the oracle's plane evaluation, bit for bit).
  double attributeUlps = 0;

  // Shader arithmetic of the manual LOD (all `precise`).
  Log2Arithmetic log2 = Log2Arithmetic::kIeee;
  double log2AbsoluteError = 0;  // kBounded: inside [0.5, 2]
  double log2Ulps = 0;           // kBounded: outside [0.5, 2]
  double sqrtUlps = 0;           // relative error of sqrt, in units of 2^-23
  double arithmeticUlps = 0;     // of +, -, * in the shader (0: correctly rounded, as the oracle)

  // Texture filtering: the sampler's GL_LINEAR (the hardware_linear sampling mode). The exact
  // sampling mode fetches texels and filters in the shader's float arithmetic.
  FilterArithmetic filter = FilterArithmetic::kFloat;
  int subTexelBits = 0;         // kBounded: texel positions snapped to 2^-subTexelBits texel
  double filterErrorUnits = 0;  // kBounded: error of the filtered value, in units of 1/255

  // Framebuffer: a float colour becomes RGBA8 by rounding to nearest (pinned) or may become either
  // of the two nearest values (GL 4.5 section 2.3.5.2).
  bool colorRoundsToNearest = true;
  // Denormals in fragment arithmetic: pinned to the arithmetic's choice, or free.
  bool denormalsPinned = true;

  // Where each parameter's value comes from, by parameter name.
  std::map<std::string, std::string> sources;

  // Every parameter pinned: each pixel's set is the oracle's one value.
  bool pinned() const;
  // Every parameter pinned but the denormal mode: each pixel's set is the oracle's value with
  // denormals flushed and its value with them kept (reference/renderer.cpp computes both).
  bool onlyDenormalsFree() const;
  bool coveragePinned() const { return subpixelBits == 8 && fillRulePinned; }
  bool operator==(const PrecisionModel&) const = default;
};

// The pinned log2 an arithmetic computes (the oracle always computes its arithmetic's own).
Log2Arithmetic log2Of(PrecisionProfile arithmetic);

PrecisionModel llvmpipeModel();
PrecisionModel softpipeModel();
// The pinned model whose arithmetic is `arithmetic`: llvmpipe, softpipe or exact.
PrecisionModel modelOfArithmetic(PrecisionProfile arithmetic);
PrecisionModel exactModel();
PrecisionModel gl45Model();

// The shipped names, for messages and command-line choices.
inline constexpr const char* kModelNames = "llvmpipe, softpipe, exact, gl45";
// Whether `name` is one of kModelNames (anything else given as a model is a model file).
bool isModelName(const std::string& name);
// A shipped model by name; throws std::invalid_argument for any other name.
PrecisionModel namedModel(const std::string& name);

// The model for an implementation's GL_RENDERER: llvmpipe on a CPU with FMA, softpipe for
// softpipe, gl45 otherwise (llvmpipe without FMA computes neither rule 8's fused polynomial nor
// the fused planes).
PrecisionModel modelForRenderer(const std::string& glRenderer);

}  // namespace vt
