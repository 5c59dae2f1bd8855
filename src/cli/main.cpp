// vt: the command line of the virtual-texturing tool chain.
//
// Exit codes: 0 success, 1 bad input or a failed operation (one line on stderr naming the file and
// the problem), 2 bad arguments (the error and the command's usage line on stderr).

#include <iostream>
#include <new>

#include "cli/commands.h"
#include "common/error.h"
#include "common/json_text.h"
#include "format/file_header.h"

#ifndef VT_VERSION
#error "VT_VERSION must be defined by the build"
#endif

namespace {

// The usage line of the innermost subcommand that was reached before the error.
std::string usageLine(const CLI::App& app) {
  const CLI::App* command = &app;
  std::string name = "vt";
  while (!command->get_subcommands().empty()) {
    command = command->get_subcommands().front();
    name += " " + command->get_name();
  }
  return CLI::Formatter().make_usage(command, name);
}

// "vt fly" for the subcommand that was running.
std::string commandName(const CLI::App& app) {
  std::string name = "vt";
  for (const CLI::App* command = &app; !command->get_subcommands().empty();) {
    command = command->get_subcommands().front();
    name += " " + command->get_name();
  }
  return name;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "vt: virtual texturing after A. Neu, \"Virtual Texturing\" (RWTH Aachen, 2010): "
      "build virtual-texture files and inspect them.",
      "vt");
  app.set_version_flag("--version",
                       std::string("vt " VT_VERSION " (virtual-texture file formats 1 to ") +
                           std::to_string(vt::kFileVersion) + ")");
  app.require_subcommand(1);
  vt::addBuildCommand(app);
  vt::addCalibrateCommand(app);
  vt::addCrosscheckCommand(app);
  vt::addInfoCommand(app);
  vt::addInspectCommand(app);
  vt::addDemoCommand(app);
  vt::addEvalCommand(app);
  vt::addExportLevelCommand(app);
  vt::addGoldenCommand(app);
  vt::addMergeCommand(app);
  vt::addFlyCommand(app);
  vt::addRenderCommand(app);
  vt::addRetextureCommand(app);
  vt::addViewCommand(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "vt: " << e.what() << '\n' << usageLine(app);
    return 2;
  } catch (const vt::InputError& e) {
    std::cerr << "vt: " << e.what() << '\n';
    return 1;
  } catch (const std::bad_alloc&) {
    // Sizes read from files are checked against the limits of common/resource_limits.h before
    // allocating; what remains is a job larger than this machine's memory.
    std::cerr << "vt: " << commandName(app)
              << ": out of memory: the inputs and arguments ask for more memory than this "
                 "machine can give\n";
    return 1;
  } catch (const nlohmann::json::exception& e) {
    std::cerr << "vt: " << commandName(app) << ": " << vt::jsonErrorText(e) << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "vt: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
