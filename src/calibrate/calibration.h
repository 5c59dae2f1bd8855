#pragma once
// `vt calibrate`: measures the precision model (render/precision_model.h) of the OpenGL
// implementation behind the current context by probe draws (probe_draws.h), the method DESIGN
// section 7 records for llvmpipe, turned into a tool. Each parameter is fitted from its own
// probes, by the narrowest hypothesis every probe agrees with:
//
//   arithmetic, attributes   random triangles (slivers, perspective, near-plane clipping, a
//                            coplanar pair): texture coordinates and their fine derivatives bit
//                            for bit as the oracle computes them with llvmpipe's fused planes,
//                            else with IEEE planes, else the largest relative error seen (ulps)
//   subpixel bits, fill rule the same triangles: every pixel's triangle as the oracle's 8-bit
//                            snapping and tie rule give it; else the fill rule is free and the
//                            sub-pixel bits are the coarsest grid that the coverage probes of
//                            coverage_fit.h (3,570 triangles at 2^-12 offsets around pixel
//                            centres) leave consistent, or gl45's where none is
//   depth                    the same triangles: the stored 32F depth bit for bit, else the
//                            largest error seen (ulps) with either rounding
//   log2, sqrt               65,536 positive floats of every exponent through log2() and sqrt():
//                            llvmpipe's polynomial or the C library's log2f bit for bit, else the
//                            largest errors seen (absolute inside [0.5, 2], ulps outside)
//   arithmetic ulps          texelFetch of the 256 unorm8 values: k * (1 / 255) as the oracle
//                            converts, and 16,384 of the shader's `precise` lerps a + (b - a) * w
//                            (bilinear rows, the trilinear blend) rounded per operation; else the
//                            largest difference in ulps
//   denormals                a denormal times a 1 read from the inputs: flushed or kept as the
//                            arithmetic does, else free
//   filter                   GL_LINEAR samples of a 16 x 16 RGBA8 texture of random texels at
//                            32,768 positions, many on and around 1/256-texel steps: llvmpipe's
//                            8-bit weights, or float weights, bit for bit; else bounded by the
//                            sub-texel bits that fit best and the largest error left
//   colour conversion        floats between two unorm8 values written to an RGBA8 target:
//                            always the nearest, else either
//
// A measured error is widened to twice the largest seen (a sample cannot prove a maximum); a
// parameter no hypothesis pins stays at its gl45 value and says so in its source. Everything is
// deterministic: the same implementation gives the same file.

#include <cstdint>
#include <string>
#include <vector>

#include "render/precision_model.h"

namespace vt::calibrate {

// The evidence for one parameter of the model.
struct ParameterFit {
  std::string parameter;  // as in model files: "log2", "filter", ...
  std::string finding;    // what the probes showed, in words
  uint64_t probes = 0;    // values compared
  uint64_t mismatches = 0;  // against the hypothesis chosen (0 when pinned)
  double largestResidual = 0;  // in the parameter's unit (ulps, 1/255, ...); 0 when pinned
  bool pinned = false;         // every probe agreed bit for bit with the chosen arithmetic
  bool fromGl45 = false;       // no hypothesis fitted: the gl45 value is kept
};

struct Calibration {
  PrecisionModel model;
  std::vector<ParameterFit> fits;
  std::string renderer, version, vendor;  // GL_RENDERER, GL_VERSION, GL_VENDOR
};

// Calibrates the implementation behind the current GL context. Throws std::runtime_error when a
// probe draw fails.
Calibration calibrate();

// The model file (precision_model_file.h) with the calibration's evidence under "calibration".
std::string calibrationJson(const Calibration& calibration);

}  // namespace vt::calibrate
