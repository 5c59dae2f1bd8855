#include "retexture/page_grid_layout.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/error.h"
#include "format/texture_description.h"
#include "retexture/cell_grid.h"

namespace vt {

Retexturing layoutOnPageGrid(const TexturedScene& scene, uint32_t pageSize) {
  const auto start = std::chrono::steady_clock::now();
  Retexturing layout;
  layout.method = "baseline";
  layout.pageSize = pageSize;
  CellGrid grid(1);
  for (const TexturedFace& face : scene.faces) {
    const SourceTexture& texture = scene.textures[face.texture];
    const TexelBounds bounds = faceTexelBounds(scene, face);
    // Whole repetitions of the texture that the face's coordinates reach.
    const double s0 = std::floor(bounds.u0 / texture.width),
                 s1 = std::ceil(bounds.u1 / texture.width);
    const double t0 = std::floor(bounds.v0 / texture.height),
                 t1 = std::ceil(bounds.v1 / texture.height);
    const double repeatsX = std::max(1.0, s1 - s0), repeatsY = std::max(1.0, t1 - t0);
    const double width = repeatsX * texture.width, height = repeatsY * texture.height;
    if (width > double(levelSide(pageSize, kMaxLevel)) ||
        height > double(levelSide(pageSize, kMaxLevel)))
      throw InputError(describedSource(scene),
                       "a face repeats its texture " + std::to_string(repeatsX) + " x " +
                           std::to_string(repeatsY) + " times: beyond the format's limit");
    TextureArea area{.texture = face.texture,
                     .sourceX = static_cast<int64_t>(s0) * texture.width,
                     .sourceY = static_cast<int64_t>(t0) * texture.height,
                     .width = static_cast<uint32_t>(width),
                     .height = static_cast<uint32_t>(height)};
    const uint64_t cellsX = (area.width + pageSize - 1) / pageSize,
                   cellsY = (area.height + pageSize - 1) / pageSize;
    std::optional<CellGrid::Cell> cell;
    while (!(cell = grid.firstFit(cellsX, cellsY))) {
      if (levelSide(pageSize, kMaxLevel) / pageSize <= grid.side())
        throw InputError(describedSource(scene),
                         "the baseline layout exceeds the format's largest texture");
      grid.grow(2 * grid.side());
    }
    grid.occupy(*cell, cellsX, cellsY);
    area.x = cell->x * pageSize;
    area.y = cell->y * pageSize;
    layout.faceArea.push_back(static_cast<uint32_t>(layout.areas.size()));
    layout.areas.push_back(area);
  }
  layout.side = grid.side() * pageSize;
  layout.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return layout;
}

}  // namespace vt
