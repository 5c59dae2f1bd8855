#pragma once
// The probe draws moved to probes/probe_draws.h, below both the calibration and vt-capture; this
// forwards for calibration.cpp and raster_fit.cpp until their next change includes it directly.
#include "probes/probe_draws.h"
