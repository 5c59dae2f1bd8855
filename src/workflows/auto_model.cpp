#include "workflows/auto_model.h"

#include "calibrate/fingerprint.h"

namespace vt {

std::optional<PrecisionModel> autoModel(const BackendContext& context, std::string* note) {
  note->clear();
  if (context.backend() != Backend::kGl) return std::nullopt;
  return calibrate::autoModel(context.renderer(), note);
}

std::string fingerprintedPoint(const BackendContext& context) {
  if (context.backend() != Backend::kGl) return "";
  return calibrate::fingerprintedPoint().value_or("");
}

}  // namespace vt
