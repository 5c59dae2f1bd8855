// vt calibrate [-o MODEL.json]: measures the precision model of the OpenGL implementation this
// machine runs (src/calibrate/calibration.h) and writes it as a model file for `vt crosscheck
// --model`, `vt golden check --model` and the oracle's API.

#include <iostream>
#include <memory>
#include <span>
#include <stdexcept>

#include "calibrate/calibration.h"
#include "calibrate/recorded_probes.h"
#include "cli/commands.h"
#include "common/output_path.h"
#include "common/posix_file.h"
#include "gl/headless_context.h"

namespace vt {

void addCalibrateCommand(CLI::App& app) {
  struct Options {
    std::string output, probes, recordProbes;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "calibrate",
      "Measure this OpenGL implementation's precision model by probe draws and write it as a "
      "model file");
  command->add_option("-o,--output", options->output, "Model file to write (default: print it)");
  command
      ->add_option("--probes", options->probes,
                   "Fit the model from probes drawn elsewhere (vt-capture probes' output folder) "
                   "instead of drawing them here; needs no OpenGL")
      ->check(CLI::ExistingDirectory);
  command->add_option("--record-probes", options->recordProbes,
                      "Also write every probe draw (request and result) into this folder, for "
                      "vt-capture to draw again on another machine");
  command->get_option("--probes")->excludes("--record-probes");
  command->callback([options] {
    if (!options->output.empty()) requireOutputFile(options->output, {options->probes});
    const calibrate::Calibration calibration = [&] {
      if (!options->probes.empty()) {
        calibrate::RecordedProbeDrawer replay(options->probes);
        const calibrate::UsingProbeDrawer using_(replay);
        return calibrate::calibrate();
      }
      const HeadlessContext context;
      if (options->recordProbes.empty()) return calibrate::calibrate();
      TemporaryFolder staging(options->recordProbes, "probes.json");
      calibrate::RecordingProbeDrawer record(staging.path());
      const calibrate::UsingProbeDrawer using_(record);
      calibrate::Calibration c = calibrate::calibrate();
      record.finish();
      staging.commit();
      return c;
    }();
    const auto evidence = [&](std::ostream& out) {
      for (const calibrate::ParameterFit& fit : calibration.fits)
        out << "  " << fit.parameter << (fit.pinned ? " [pinned]" : " [bounded]") << ": "
            << fit.finding << " (" << fit.probes << " values)\n";
    };
    if (!calibration.conformant()) {
      std::cerr << "vt calibrate: " << calibration.renderer << " (" << calibration.version
                << "), what the probes found:\n";
      evidence(std::cerr);
      // No model: a bound wide enough to pass this implementation would pass its bug too.
      for (const std::string& line : calibration.conformance)
        std::cerr << "vt calibrate: " << calibration.renderer << " breaks a rule: " << line << "\n";
      throw std::runtime_error(calibration.renderer + " is not conformant (" +
                               std::to_string(calibration.conformance.size()) +
                               " rules broken, above): no model written");
    }
    const std::string json = calibrate::calibrationJson(calibration);
    if (options->output.empty()) {
      std::cout << json;
      return;
    }
    writeFileAtomically(options->output, std::as_bytes(std::span(json.data(), json.size())));
    std::cout << "calibrated " << calibration.renderer << " (" << calibration.version << "): wrote "
              << options->output << "\n";
    evidence(std::cout);
  });
}

}  // namespace vt
