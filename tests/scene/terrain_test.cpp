// The heightmap terrain (thesis 4.4): one continuous texture area over hills.

#include "scene/terrain.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace vt {
namespace {

TEST(Terrain, IsAGridOnItsHeightmapWithOneContinuousTextureArea) {
  const TerrainShape shape{.cells = 16, .extent = 100.0f, .amplitude = 5.0f, .seed = 3};
  const Mesh mesh = heightmapTerrain(shape);
  ASSERT_EQ(mesh.positions.size(), 17u * 17u);
  ASSERT_EQ(mesh.indices.size(), 16u * 16u * 6u);
  float low = 0.0f, high = 0.0f;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    EXPECT_EQ(p.y, terrainHeight(shape, p.x, p.z));
    EXPECT_LE(std::abs(p.y), shape.amplitude);
    // s and t follow x and z over [0, 1]: neighbouring cells continue each other's texels.
    EXPECT_NEAR(mesh.uvs[v].x, p.x / shape.extent + 0.5f, 1e-6f);
    EXPECT_NEAR(mesh.uvs[v].y, p.z / shape.extent + 0.5f, 1e-6f);
    low = std::min(low, p.y), high = std::max(high, p.y);
  }
  EXPECT_GT(high - low, shape.amplitude);  // hills, not a plane
  // Every triangle faces up (counter-clockwise seen from +y).
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                    c = mesh.positions[mesh.indices[t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);
  }
}

TEST(Terrain, SameSeedSameHillsOtherSeedOtherHills) {
  const TerrainShape a{.seed = 7}, b{.seed = 8};
  EXPECT_EQ(heightmapTerrain(a).positions, heightmapTerrain(a).positions);
  EXPECT_NE(heightmapTerrain(a).positions, heightmapTerrain(b).positions);
  const Camera camera = terrainCamera(a);
  EXPECT_GT(camera.position.y, terrainHeight(a, camera.position.x, camera.position.z));
}

}  // namespace
}  // namespace vt
