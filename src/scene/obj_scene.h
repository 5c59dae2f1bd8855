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

#include "scene/textured_scene.h"

namespace vt {

// The checker image, when needed, is written into `imageFolder`.
TexturedScene loadObjScene(const std::filesystem::path& path,
                           const std::filesystem::path& imageFolder);

}  // namespace vt
