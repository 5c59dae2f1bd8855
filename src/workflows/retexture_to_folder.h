#pragma once
// `vt retexture`'s work as one call (thesis 3.3.2): a Quake 3 map from its packages, or an OBJ
// scene, given its own texture areas, written into a folder that takes the output's place once
// complete (the retextured mesh, the layout for `vt build`, a report comparing the thesis's layout
// with ours, a tour of its viewpoints, extracted images), with one line per layout method.

#include <filesystem>
#include <ostream>
#include <vector>

#include "retexture/retexture.h"
#include "scene/quake3_scene.h"

namespace vt {

struct RetextureRequest {
  std::filesystem::path scene;  // an .obj file, or a map's name
  bool obj = false;
  std::vector<std::filesystem::path> packages;  // a map's .pk3 folders, later ones override
  RetextureOptions options;
  uint32_t border = 4;  // the layout's page border
  int patchLevel = kPatchTessellationLevel;
  std::filesystem::path output;
};

void retextureToFolder(const RetextureRequest& request, std::ostream& out, std::ostream& err);

}  // namespace vt
