#pragma once
// What `vt retexture` writes, each file through a temporary file renamed at the end:
// - the retextured mesh: OBJ with the new coordinates (v = 1 - t', as OBJ images have v up), one
//   group per face ("face_<n>"), so a face of the report can be found in the mesh;
// - the layout for `vt build` (build/layout.h): one region placement per area, image paths
//   relative to the layout's folder;
// - the report (JSON): the scene's counts and warnings, and both methods side by side;
// - a camera path through the scene's viewpoints.

#include <filesystem>

#include "retexture/retexture.h"

namespace vt {

void writeRetexturedObj(const std::filesystem::path& path, const TexturedScene& scene,
                        const std::vector<glm::vec2>& uvs);

struct LayoutSettings {
  uint32_t border = 4;
};

void writeRetextureLayout(const std::filesystem::path& path, const TexturedScene& scene,
                          const Retexturing& layout, const LayoutSettings& settings);

// A camera path (scene/camera_path.h) through the coherence views (page_coherence.h): at each
// viewpoint a turn in four quarters, then on to the next, a keyframe every 24 frames; for
// `vt fly` and `vt crosscheck --mesh --path`.
void writeViewpointTour(const std::filesystem::path& path, const TexturedScene& scene);

void writeRetextureReport(const std::filesystem::path& path, const TexturedScene& scene,
                          const RetextureResult& result, const RetextureOptions& options);

}  // namespace vt
