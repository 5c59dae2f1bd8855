#pragma once
// The calibration's probe draws as files, so that they can be drawn on one machine and fitted on
// another (`vt-capture probes`, then `vt calibrate --probes`). A folder holds, per draw i in the
// order `vt calibrate` makes them:
//   probe-NNNN.json          the request: {"format": "vt-probe", "version": 1, "kind": "shader",
//                            "colour" or "triangles", and the fields below}
//   probe-NNNN.inputs.f32    shader/colour: four little-endian float32 per pixel ("input_count"
//                            of them, "width" per row); "body" the fragment code; "clipped",
//                            "linear" as in probes/probe_draws.h
//   probe-NNNN.texels.rgba8  shader/colour with a texture: "texture_size" [w, h], RGBA8 rows
//   probe-NNNN.vertices.f32  triangles: six float32 per vertex (x, y, z, w, s, t), "vertex_count"
//   probe-NNNN.indices.u32   triangles: "index_count" uint32; "viewport" [w, h]; "depth"
//                            "depth32f" or "depth24"
//   probe-NNNN.result        what the implementation drew: shader: four float32 per input;
//                            colour: four bytes per input; triangles: per pixel (bottom row
//                            first) int32 triangle, float32 s, t, ds/dx, dt/dx, ds/dy, dt/dy, depth
// and probes.json: {"format": "vt-probes", "version": 1, "count", "renderer", "version_string",
// "vendor"}; the function sweeps beside them are capture/sweep_files.h's. Every size is checked
// against its limit and against the request before anything is allocated; a file that disagrees
// is refused with its name.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "probes/probe_draws.h"

namespace vt::capture {

struct ProbeRequest {
  enum class Kind { kShader, kColour, kTriangles };
  Kind kind = Kind::kShader;
  calibrate::ShaderProbe shader;  // kShader, kColour
  ClipSpaceMesh mesh;             // kTriangles
  Viewport viewport;
  DepthFormat depth = DepthFormat::kDepth32F;
  calibrate::Interpolation interpolation = calibrate::Interpolation::kPerspective;  // kTriangles
};

struct ProbeResult {
  std::vector<glm::vec4> values;      // kShader
  std::vector<glm::u8vec4> bytes;     // kColour
  calibrate::RasterReadback raster;  // kTriangles
};

bool sameRequest(const ProbeRequest& a, const ProbeRequest& b);

// Files of draw `index` in `folder` (which must exist).
void writeProbeRequest(const std::filesystem::path& folder, size_t index,
                       const ProbeRequest& request);
ProbeRequest readProbeRequest(const std::filesystem::path& folder, size_t index);
void writeProbeResult(const std::filesystem::path& folder, size_t index,
                      const ProbeRequest& request, const ProbeResult& result);
ProbeResult readProbeResult(const std::filesystem::path& folder, size_t index,
                            const ProbeRequest& request);

// probes.json: how many draws the folder holds and who drew them.
struct ProbeFolder {
  size_t count = 0;
  calibrate::ProbeIdentity identity;
};
void writeProbeFolder(const std::filesystem::path& folder, const ProbeFolder& description);
ProbeFolder readProbeFolder(const std::filesystem::path& folder);
// The number of requests probe-0000.json, probe-0001.json, ... in a folder without probes.json.
size_t countProbeRequests(const std::filesystem::path& folder);

// The request drawn on the current context.
ProbeResult drawHere(const ProbeRequest& request);

}  // namespace vt::capture
