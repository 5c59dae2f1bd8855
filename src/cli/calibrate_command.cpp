// vt calibrate [-o MODEL.json]: measures the precision model of the OpenGL implementation this
// machine runs (src/calibrate/calibration.h) and writes it as a model file for `vt crosscheck
// --model`, `vt golden check --model` and the oracle's API.

#include <iostream>
#include <memory>
#include <span>

#include "calibrate/calibration.h"
#include "cli/commands.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "gl/headless_context.h"

namespace vt {

void addCalibrateCommand(CLI::App& app) {
  struct Options {
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "calibrate",
      "Measure this OpenGL implementation's precision model by probe draws and write it as a "
      "model file");
  command->add_option("-o,--output", options->output,
                      "Model file to write (default: print it)");
  command->callback([options] {
    if (!options->output.empty()) requireOutputFile(options->output, {});
    const HeadlessContext context;
    const calibrate::Calibration calibration = calibrate::calibrate();
    const std::string json = calibrate::calibrationJson(calibration);
    if (options->output.empty()) {
      std::cout << json;
      return;
    }
    writeFileAtomically(options->output, std::as_bytes(std::span(json.data(), json.size())));
    std::cout << "calibrated " << calibration.renderer << " (" << calibration.version
              << "): wrote " << options->output << "\n";
    for (const calibrate::ParameterFit& fit : calibration.fits)
      std::cout << "  " << fit.parameter << ": " << fit.finding << " (" << fit.probes
                << " values)\n";
  });
}

}  // namespace vt
