#pragma once
// The subcommands of `vt`, one file each. Each adds itself to the application; its callback runs
// the command and throws InputError for bad input, which main() prints as one line.

#include <CLI/CLI.hpp>

namespace vt {

void addBuildCommand(CLI::App& app);
void addCalibrateCommand(CLI::App& app);
void addCrosscheckCommand(CLI::App& app);
void addInfoCommand(CLI::App& app);
void addInspectCommand(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addExportLevelCommand(CLI::App& app);
void addGoldenCommand(CLI::App& app);
void addMergeCommand(CLI::App& app);
void addFlyCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addRetextureCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

}  // namespace vt
