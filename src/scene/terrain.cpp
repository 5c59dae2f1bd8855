#include "scene/terrain.h"

#include <cmath>
#include <random>

namespace vt {

float terrainHeight(const TerrainShape& shape, float x, float z) {
  // Octaves of decreasing wavelength and amplitude; std::mt19937's sequence is fixed by the
  // standard, so every platform draws the same hills.
  std::mt19937 random(shape.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  constexpr int kOctaves = 5;
  const float twoPi = 6.28318531f;
  float height = 0.0f, weight = 0.5f, total = 0.0f;
  for (int octave = 0; octave < kOctaves; ++octave, weight *= 0.5f) {
    const float angle = twoPi * unit(random), phase = twoPi * unit(random);
    const float wavelength = shape.extent / static_cast<float>(2 << octave);
    const float along = (std::cos(angle) * x + std::sin(angle) * z) / wavelength;
    const float across = (-std::sin(angle) * x + std::cos(angle) * z) / wavelength;
    height += weight * std::sin(twoPi * along + phase) * std::cos(0.7f * twoPi * across);
    total += weight;
  }
  return shape.amplitude * height / total;
}

Mesh heightmapTerrain(const TerrainShape& shape) {
  Mesh mesh;
  const uint32_t n = shape.cells;
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n; ++i) {
      const float s = static_cast<float>(i) / static_cast<float>(n);
      const float t = static_cast<float>(j) / static_cast<float>(n);
      const float x = (s - 0.5f) * shape.extent, z = (t - 0.5f) * shape.extent;
      mesh.positions.emplace_back(x, terrainHeight(shape, x, z), z);
      mesh.uvs.emplace_back(s, t);
    }
  // Counter-clockwise seen from above (+y): x grows with i, z with j.
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

Camera terrainCamera(const TerrainShape& shape) {
  Camera camera;
  const float x = 0.0f, z = 0.45f * shape.extent;
  camera.position = {x, terrainHeight(shape, x, z) + 0.4f * shape.amplitude, z};
  camera.target = {0.1f * shape.extent, 0.0f, 0.0f};
  camera.nearPlane = 0.1f;
  camera.farPlane = 2.0f * shape.extent;
  return camera;
}

}  // namespace vt
