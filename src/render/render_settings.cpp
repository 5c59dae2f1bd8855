#include "render/render_settings.h"

namespace vt {

void applyModel(RenderSettings& settings, const PrecisionModel& model) {
  settings.arithmetic = model.arithmetic;
  settings.model = std::make_shared<const PrecisionModel>(model);
}

}  // namespace vt
