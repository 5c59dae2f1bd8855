#pragma once
// `vt calibrate`: measures the OpenGL implementation behind the current context, family by family
// (render/arithmetic.h), by probe draws (probes/probe_draws.h), and writes the precision model it pins.
//
//   shader math    log2, sqrt, texel values, the `precise` lerps, denormals (shader_math_fit.h)
//   GL_LINEAR      every member of the filter family (filter_fit.h)
//   rasterization  coverage, viewport, plane setup and evaluation, perspective, depth
//                  (raster_fit.h); the planes of noperspective coordinates, evidence where the
//                  folder holds that group (noperspective_fit.h)
//   reciprocal     1.0 / x over a binade, evidence where the folder holds the sweep
//                  (shader_math_fit.h)
//   colour         floats between two unorm8 values written to an RGBA8 target: always the
//                  nearest, else either (GL 4.5 section 2.3.5.2)
//   depth test     a far quad drawn after a near one and a near one after a far one, 32F depth,
//                  GL_LESS: every covered pixel must show the near quad (GL 4.5 section 17.3, the
//                  depth buffer test)
//
// Each family is pinned where a member reproduces every probe bit for bit; the oracle then draws
// with that member. A family no member reproduces is bounded by the residual measured against
// the closest member (the largest error seen, in the model's unit, not rounded up). A calibrated
// model is always within gl45 (precision_model.h): a measurement beyond it, or a pixel that
// breaks the depth test, is non-conformance, reported in `conformance` with the rule, its
// specification section, the probe and the value; `vt calibrate` then writes no model and exits
// 1. Everything is deterministic: the same implementation gives the same file.

#include <string>
#include <vector>

#include "calibrate/family_fit.h"
#include "render/precision_model.h"

namespace vt::calibrate {

struct Calibration {
  PrecisionModel model;
  std::vector<ParameterFit> fits;
  std::string renderer, version, vendor;  // GL_RENDERER, GL_VERSION, GL_VENDOR
  // Empty for a conformant implementation; else what broke a rule, one line each.
  std::vector<std::string> conformance;
  bool conformant() const { return conformance.empty(); }
};

// Calibrates the implementation behind the current GL context. Throws std::runtime_error when a
// probe draw fails.
Calibration calibrate();

// The model file (precision_model_file.h) with the calibration's evidence under "calibration".
std::string calibrationJson(const Calibration& calibration);

}  // namespace vt::calibrate
