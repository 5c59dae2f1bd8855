#pragma once
// The command line's frames, meshes and cache states in the terms of the oracle's public API
// (<vt/oracle.h>), which the commands that compare renderers go through.

#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "reference/cache_state.h"
#include "reference/renderer.h"
#include "scene/clip_space_mesh.h"
#include "vt/oracle.h"

namespace vt {

oracle::Scene publicScene(const ClipSpaceMesh& mesh, Viewport viewport);
// Each resident page in the frame its indirection entry names.
oracle::CacheState publicCacheState(const reference::CacheState& cache);
oracle::RenderOptions publicRenderOptions(const reference::RenderSettings& settings);
// Four values per pixel.
std::vector<uint32_t> flatNeed(std::span<const glm::uvec4> need);

}  // namespace vt
