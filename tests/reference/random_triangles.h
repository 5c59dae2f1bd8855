#pragma once
// Scenes for the visibility tests: random overlapping triangles in clip space, perspective and
// depth varied, followed by two coplanar copies of the first (the earlier drawn must win).

#include <random>

#include "scene/clip_space_mesh.h"

namespace vt::test {

inline ClipSpaceMesh randomTrianglesWithCoplanarCopies(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-1.5f, 1.5f), depth(-0.9f, 0.9f), w(0.5f, 2.0f);
  ClipSpaceMesh mesh;
  for (int k = 0; k < count; ++k)
    for (int corner = 0; corner < 3; ++corner) {
      const float vw = w(random);
      mesh.vertices.push_back(
          {{coordinate(random) * vw, coordinate(random) * vw, depth(random) * vw, vw},
           {0.5f, 0.5f}});
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  for (int copy = 0; copy < 2; ++copy)
    for (int corner = 0; corner < 3; ++corner) {
      mesh.vertices.push_back(mesh.vertices[static_cast<size_t>(corner)]);
      mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
    }
  return mesh;
}

}  // namespace vt::test
