#pragma once
// Named scenes for cross-checks and debugging: the box room and the extreme cases of the
// numerical stability suite, as meshes with cameras. Texture coordinates lie in [0, 1], so any
// virtual texture can be drawn on them.
//
//   room       the box room (box_room.h)
//   grazing    a plane seen at 89.9 degrees from its normal
//   horizon    a ground plane reaching the horizon (helper pixels beyond w = 0)
//   coplanar   two coplanar overlapping quads with different texture areas (decals)
//   minified   a whole texture on a few hundred pixels, and a magnified corner
//   terrain    hills from a heightmap under one continuous texture area (terrain.h)
//   occluders  a wall with a panel drawn before it and a box drawn after it, well in front: what
//              the depth test decides, whatever the draw order
//   crossing   two large quads crossing at an angle: a depth-decided intersection line

#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/camera_path.h"
#include "scene/mesh.h"

namespace vt {

struct NamedScene {
  std::string name;
  Mesh mesh;
  Camera camera;
};

std::vector<std::string> testSceneNames();
// Throws std::invalid_argument for an unknown name.
NamedScene testScene(const std::string& name);

// The test scenes of a comma-separated list of names, or every one for "all".
std::vector<NamedScene> namedSceneViews(const std::string& list);

// Every `every`-th frame of `path` through `mesh`, named frame0000, frame0008, ...
std::vector<NamedScene> flythroughViews(const Mesh& mesh, const CameraPath& path, int every);

}  // namespace vt
