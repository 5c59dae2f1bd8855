#pragma once
// A Wavefront OBJ file with its MTL materials as a textured scene (tinyobjloader): each polygon is
// a face (fan-triangulated), textured by its material's diffuse map (map_Kd, relative to the
// folder of the MTL file that defines the material). OBJ's v is flipped to t = 1 - v (t along the
// image's rows).
//
// Errors naming the file: a missing OBJ, an `mtllib` that does not exist, a face without texture
// coordinates, an index out of range. A vertex that is not finite skips its face (counted). A
// face without a material, or whose material has no map_Kd or an unreadable one, gets the checker
// image and a warning.

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/image_file.h"
#include "scene/textured_scene.h"

namespace vt {

// The checker image, when needed, is written into `imageFolder`.
TexturedScene loadObjScene(const std::filesystem::path& path,
                           const std::filesystem::path& imageFolder);

// An OBJ scene's text held in memory: the OBJ and each material library its `mtllib` lines name,
// by that name. `path` names the OBJ in errors, and map_Kd images are found relative to its
// folder as for a file, their headers read by `imageHeader` (by default OpenImageIO's).
struct ObjSceneText {
  std::filesystem::path path;
  std::string obj;
  std::map<std::string, std::string> materialLibraries;
  std::function<std::optional<ImageHeader>(const std::filesystem::path&)> imageHeader = {};
};
TexturedScene loadObjScene(const ObjSceneText& source, const std::filesystem::path& imageFolder);

// The material libraries the `mtllib` lines of an OBJ text name, in order.
std::vector<std::string> materialLibraryNames(std::string_view objText);

}  // namespace vt
