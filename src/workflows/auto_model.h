#pragma once
// What `--model auto` means for the implementation a BackendContext draws with, resolved here,
// above the renderer factory (backends/backend.h), so that the factory links no calibration: the
// commands resolve it and pass the model down.

#include <optional>
#include <string>

#include "backends/backend.h"
#include "render/precision_model.h"

namespace vt {

// The verifier's one resolution of `auto` (calibrate/fingerprint.h, autoModel): a measured or
// shipped model whose fingerprint reproduces on the context's GL implementation, else gl45, with
// one line in `note` saying why. None for the oracle, which draws whatever arithmetic it is
// given: the caller's own default applies.
std::optional<PrecisionModel> autoModel(const BackendContext& context, std::string* note);

// The named point the context's GL implementation reproduces, recorded in captures; "" where none
// does, and for the oracle.
std::string fingerprintedPoint(const BackendContext& context);

}  // namespace vt
