#pragma once
// The command line's frames, meshes and cache states in the terms of the oracle's public API
// (<vt/oracle.h>), which the commands that compare renderers go through. Meshes and needbuffers
// convert with the API implementation's own oracle::publicScene and oracle::flatNeed.

#include "reference/api/api_internal.h"
#include "render/frame_comparison.h"
#include "reference/renderer.h"
#include "render/cache_state.h"
#include "scene/clip_space_mesh.h"
#include "vt/oracle.h"

namespace vt {

// Each resident page in the frame its indirection entry names.
oracle::CacheState publicCacheState(const CacheState& cache);
oracle::RenderOptions publicRenderOptions(const RenderSettings& settings,
                                          const std::string& modelFile = "");
// How tight the verdict on an oracle frame is (SetWidths): from its result sets, or
// under a pinned model from its needbuffer. The public API's Comparison does not carry them.
SetWidths verdictWidths(const oracle::Frame& frame);

}  // namespace vt
