#pragma once
// A terrain from a heightmap (thesis 4.4: outdoor scenes, one continuous texture area over the
// whole ground): a grid of cells x cells squares over [-extent/2, extent/2]^2 in x and z, heights
// from a smooth deterministic heightmap (a sum of sine waves whose directions and phases come
// from `seed`), texture coordinates s = x / extent + 1/2, t = z / extent + 1/2 over [0, 1].

#include <cstdint>

#include "scene/camera.h"
#include "scene/mesh.h"

namespace vt {

struct TerrainShape {
  uint32_t cells = 96;
  float extent = 200.0f;    // side of the square, world units
  float amplitude = 12.0f;  // largest height above or below zero
  uint32_t seed = 1;
};

// The height at (x, z); the mesh's vertices lie exactly on it.
float terrainHeight(const TerrainShape& shape, float x, float z);

Mesh heightmapTerrain(const TerrainShape& shape);

// A camera above the ground near one edge, looking across the hills.
Camera terrainCamera(const TerrainShape& shape);

}  // namespace vt
