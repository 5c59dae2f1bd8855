#pragma once
// The named points of the arithmetic space (arithmetic.h): implementations whose arithmetic was
// read from their source or measured bit for bit. This file and its .cpp are the only places that
// name an implementation; everything else asks an Arithmetic for its choices.
//
//   exact     IEEE float in the order the source states it: no fused multiply-add, denormals
//             kept, log2 from the C library. The reference for golden images.
//   llvmpipe  Mesa 22.3 llvmpipe on x86-64 with FMA (docs/design.md section 7, measured).
//   softpipe  Mesa 22.3 softpipe (reference/softpipe-arithmetic.md, read from its source and
//             confirmed by emulation).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/arithmetic.h"
#include "render/precision_model.h"

namespace vt {

// The named points, in the order messages list them.
std::vector<std::string> arithmeticPointNames();
// "exact, llvmpipe, softpipe".
std::string joinedArithmeticPointNames();
std::optional<Arithmetic> findArithmeticPoint(std::string_view name);
// Throws std::invalid_argument naming the points for any other name.
Arithmetic arithmeticPoint(std::string_view name);
// The name of the point `arithmetic` is, or "" for a point no implementation has a name for.
std::string arithmeticPointName(const Arithmetic& arithmetic);
// The point's name, or "calibrated" for a point without one (messages and reports).
std::string arithmeticLabel(const Arithmetic& arithmetic);
// The point for an implementation's GL_RENDERER, when its arithmetic is known without probing it
// (the fingerprint of precision_model_file.h must still confirm it): llvmpipe on a CPU with FMA,
// softpipe; none otherwise.
std::optional<std::string> pointForRenderer(const std::string& glRenderer);

// The shipped models of the named points: every parameter pinned (softpipe's denormal mode
// aside, which it changes between batches: precision_model.h, onlyDenormalsFree).
PrecisionModel llvmpipeModel();
PrecisionModel softpipeModel();
PrecisionModel exactModel();

// The shipped names, for messages and command-line choices.
inline constexpr const char* kModelNames = "llvmpipe, softpipe, exact, gl45";
// Whether `name` is one of kModelNames (anything else given as a model is a model file).
bool isModelName(const std::string& name);
// A shipped model by name; throws std::invalid_argument for any other name.
PrecisionModel namedModel(const std::string& name);

// The pinned model an implementation's GL_RENDERER suggests (arithmetic_points.h), gl45 when it
// suggests none. A suggestion only: where a GL context is at hand, `auto` confirms it by a
// fingerprint first (calibrate/fingerprint.h).
PrecisionModel modelForRenderer(const std::string& glRenderer);

// A version 1 model file's arithmetic (precision_model_file.h): `point` a point's name, `log2` and
// `filter` a member named after a point ("llvmpipe", "softpipe", "ieee"; "llvmpipe_8bit",
// "float") or "bounded". False for names version 1 did not have.
bool readVersion1Arithmetic(const std::string& point, const std::string& log2,
                            const std::string& filter, PrecisionModel& model);

}  // namespace vt
