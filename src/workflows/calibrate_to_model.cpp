#include "workflows/calibrate_to_model.h"

#include <span>
#include <stdexcept>
#include <string>

#include "calibrate/recorded_probes.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "gl/headless_context.h"
#include "render/precision_model_file.h"

namespace vt {

calibrate::Calibration calibrateToModel(const CalibrateRequest& request, std::ostream& out,
                                        std::ostream& err) {
  const calibrate::Calibration calibration = [&] {
    if (!request.probes.empty()) {
      calibrate::RecordedProbeDrawer replay(request.probes);
      const calibrate::UsingProbeDrawer using_(replay);
      return calibrate::calibrate();
    }
    const HeadlessContext context;
    if (request.recordProbes.empty()) return calibrate::calibrate();
    TemporaryFolder staging(request.recordProbes, "probes.json");
    calibrate::RecordingProbeDrawer record(staging.path());
    const calibrate::UsingProbeDrawer using_(record);
    calibrate::Calibration c = calibrate::calibrate();
    record.finish();
    staging.commit();
    return c;
  }();
  const auto evidence = [&](std::ostream& stream) {
    for (const calibrate::ParameterFit& fit : calibration.fits)
      stream << "  " << fit.parameter << (fit.pinned ? " [pinned]" : " [bounded]") << ": "
             << fit.finding << " (" << fit.probes << " values)\n";
  };
  if (!calibration.conformant()) {
    err << "vt calibrate: " << calibration.renderer << " (" << calibration.version
        << "), what the probes found:\n";
    evidence(err);
    // No model: a bound wide enough to pass this implementation would pass its bug too.
    for (const std::string& line : calibration.conformance)
      err << "vt calibrate: " << calibration.renderer << " breaks a rule: " << line << "\n";
    throw std::runtime_error(calibration.renderer + " is not conformant (" +
                             std::to_string(calibration.conformance.size()) +
                             " rules broken, above): no model written");
  }
  const std::string json = calibrate::calibrationJson(calibration);
  if (request.output.empty()) {
    out << json;
    for (const auto& table : {calibration.model.arithmetic.reciprocal.table,
                              calibration.model.arithmetic.sqrt.table,
                              calibration.model.arithmetic.log2Table.table})
      if (table)
        err << "vt calibrate: the model names its measured table "
            << tableFileName(table->function(), table->checksum())
            << ", which only -o writes beside it\n";
    return calibration;
  }
  writeModelFiles(request.output, calibration.model.arithmetic, json);
  out << "calibrated " << calibration.renderer << " (" << calibration.version << "): wrote "
      << request.output.string() << "\n";
  evidence(out);
  return calibration;
}

}  // namespace vt
