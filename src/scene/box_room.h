#pragma once
// The default scene's geometry until retextured maps replace it: a box room 8 x 3 x 6 units,
// each face mapped to one material area of the default scene's texture (build/demo_scene.h):
// planks on the floor, sky on the ceiling, bricks, tiles and marble on the walls.

#include "scene/camera.h"
#include "scene/mesh.h"

namespace vt {

Mesh boxRoom();

// A camera in a corner of the room looking across it.
Camera boxRoomCamera();

}  // namespace vt
