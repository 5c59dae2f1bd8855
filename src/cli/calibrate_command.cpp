// vt calibrate [-o MODEL.json]: measures the precision model of the OpenGL implementation this
// machine runs (src/calibrate/calibration.h) and writes it as a model file for `vt crosscheck
// --model`, `vt golden check --model` and the oracle's API.

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "common/output_path.h"
#include "workflows/calibrate_to_model.h"

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
    calibrateToModel({.output = options->output,
                      .probes = options->probes,
                      .recordProbes = options->recordProbes},
                     std::cout, std::cerr);
  });
}

}  // namespace vt
