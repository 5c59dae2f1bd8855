#pragma once
// What the oracle draws: triangles of clip-space vertices with virtual texture coordinates, as an
// engine hands them to the rasterizer (the output of its vertex stage). Triangles are drawn in
// order with the depth test GL_LESS into a 32-bit float depth buffer cleared to 1; clip z lies in
// [-w, w] (OpenGL conventions); the viewport covers the whole frame, window y up.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "vt/oracle/export.h"

namespace vt::oracle {

struct Viewport {
  int width = 0, height = 0;  // pixels
};

struct ClipVertex {
  float x = 0, y = 0, z = 0, w = 1;  // clip space
  float s = 0, t = 0;                // virtual texture coordinates, [0, 1] covers the texture
};

struct Scene {
  Viewport viewport;
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;  // three per triangle; empty: vertices 3k, 3k + 1, 3k + 2
};

// A pinhole camera looking from `position` at `target` (OpenGL view space, vertical field of view
// in degrees).
struct Camera {
  float position[3] = {0, 0, 3};
  float target[3] = {0, 0, 0};
  float up[3] = {0, 1, 0};
  float fovYDegrees = 60;
  float nearPlane = 0.05f, farPlane = 1000;
};

// The triangles of an OBJ mesh (its texture coordinates are virtual texture coordinates, as
// `vt retexture` writes them) seen by `camera`: the transform both of this project's renderers
// use. Throws Error naming the file when it cannot be read.
VT_ORACLE_API Scene sceneFromObj(const std::filesystem::path& obj, const Camera& camera,
                                 Viewport viewport);

}  // namespace vt::oracle
