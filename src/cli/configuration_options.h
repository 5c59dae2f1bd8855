#pragma once
// The command-line options that make one FlightConfiguration (eval/flight_configuration.h), shared
// by `vt fly`, `vt inspect` and `vt golden generate`: the same names as the JSON keys, with
// dashes. `--config FILE` reads a configuration from JSON instead, or with `--config-name NAME`
// the configuration of that name from a configurations file (eval/configurations_file.h);
// options given as well override its values.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <vector>

#include "eval/flight_configuration.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

// What a flight flies over: the texture, the mesh and the camera path (both defaulting to the box
// room and its turn) and the screen size; shared by `vt fly`, `vt eval` and `vt inspect`.
struct FlightSceneArguments {
  std::string texture, path, mesh, size = "320x200";

  void addTo(CLI::App* command);
  CameraPath cameraPath() const;  // the file (keyframes or storyboard), or the box room's turn
  Mesh loadMesh() const;          // the OBJ file, or the box room
  std::string sceneName() const;
  // The files read: for requireOutputFile/Folder (common/output_path.h).
  std::vector<std::filesystem::path> inputs() const { return {texture, path, mesh}; }
};

class ConfigurationOptions {
 public:
  explicit ConfigurationOptions(CLI::App* command);
  // After parsing: the configuration (throws InputError for a bad --config file).
  FlightConfiguration configuration() const;
  // The --config file, empty without one.
  std::filesystem::path file() const;

 private:
  struct Values;
  // The options of page selection beyond the thesis (docs/streaming.md).
  void addBeyondTheThesisOptions();
  std::shared_ptr<Values> values_;
  CLI::App* command_;
};

}  // namespace vt
