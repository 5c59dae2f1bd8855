#pragma once
// The thesis's layout (3.3.2, 3.3.2.1), our baseline: each face gets a copy of its whole source
// texture, repeated as often as its coordinates repeat it (whole repetitions, from floor(s_min)
// to ceil(s_max)); the copy is rounded up to whole page-sized cells of a grid and placed by first
// fit (rows top to bottom, cells left to right); when no free block is large enough the grid
// doubles its side (the texture the next resolution up), keeping what was placed.

#include <cstdint>

#include "retexture/texture_area.h"

namespace vt {

// Throws InputError naming the scene when the texture would exceed the format's largest side.
Retexturing layoutOnPageGrid(const TexturedScene& scene, uint32_t pageSize);

}  // namespace vt
