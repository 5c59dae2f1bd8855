#pragma once
// `auto` verifies before it trusts (docs/design.md section 3): a pinned model is used for an
// implementation only after a fingerprint of it, a handful of probe draws on the current GL
// context, reproduces the model's arithmetic bit for bit. The renderer's name decides nothing.
//
// The fingerprint (well under a second): log2 of 4,096 floats of every exponent, and their
// reciprocals and square roots where the model's are measured tables (render/measured_table.h);
// 256 texel
// fetches of unorm8 values; 4,096 GL_LINEAR samples of a 24 x 40 texture at random coordinates;
// 40 random triangles at 64 x 48 (which triangle, texture coordinates, fine derivatives, 32F
// depth); and, where the model pins it, a denormal product in a clipped and an unclipped draw.

#include <optional>
#include <string>

#include "render/arithmetic.h"
#include "render/precision_model.h"

namespace vt::calibrate {

struct Fingerprint {
  bool reproduced = false;
  std::string finding;  // the first family that differed, in words; empty when reproduced
};

// Draws the fingerprint on the current context and compares it with `arithmetic`; denormals
// only when `denormalsPinned`.
Fingerprint fingerprint(const Arithmetic& arithmetic, bool denormalsPinned = true);

// The model "auto" means on the current context for an implementation named `glRenderer`: a
// measured model of it ($VT_PRECISION_MODELS; a pinned one only when its fingerprint
// reproduces), else the first named point whose fingerprint reproduces, else gl45. `note`
// receives one line when a pinned model was refused or none reproduced (empty otherwise).
PrecisionModel autoModel(const std::string& glRenderer, std::string* note);

// `nameOrFile` as resolveModel (render/precision_model_file.h) reads it, with "auto" as
// autoModel on the current context.
PrecisionModel resolveModelHere(const std::string& nameOrFile, const std::string& glRenderer,
                                std::string* note);

// The named point the current context reproduces, if any (captures record it).
std::optional<std::string> fingerprintedPoint();

}  // namespace vt::calibrate
