#pragma once
// `vt calibrate`'s work as one call: the calibration (calibrate/calibration.h) drawn on a new
// headless context, or replayed from probes drawn elsewhere, or drawn here and recorded for
// elsewhere; the evidence per family; the model file written (or printed), or, for an
// implementation that breaks a rule, the rules it breaks and no model (std::runtime_error).

#include <filesystem>
#include <ostream>

#include "calibrate/calibration.h"

namespace vt {

struct CalibrateRequest {
  std::filesystem::path output;        // the model file; empty: printed to `out`
  std::filesystem::path probes;        // replay these probe draws instead of drawing
  std::filesystem::path recordProbes;  // also record every probe draw here
};

calibrate::Calibration calibrateToModel(const CalibrateRequest& request, std::ostream& out,
                                        std::ostream& err);

}  // namespace vt
