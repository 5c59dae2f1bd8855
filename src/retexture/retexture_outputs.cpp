#include "retexture/retexture_outputs.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "common/posix_file.h"
#include "retexture/page_coherence.h"

namespace vt {
namespace {

using nlohmann::ordered_json;

ordered_json methodJson(const MethodResult& method) {
  ordered_json json = {
      {"side", method.layout.side},
      {"areas", method.layout.areas.size()},
      {"finest_pages_allocated", method.quality.finestPages},
      {"pages_allocated_all_levels", method.quality.allPages},
      {"referenced_texels", method.quality.referencedTexels},
      {"referenced_fraction", method.quality.referencedFraction},
      {"layout_seconds", method.layout.seconds},
  };
  if (method.coherence) {
    json["coherence_views"] = method.coherence->views;
    json["pages_per_1000_pixels"] = method.coherence->pagesPer1000Pixels;
    json["pages_per_view"] = method.coherence->meanPagesPerView;
  }
  return json;
}

}  // namespace

void writeRetexturedObj(const std::filesystem::path& path, const TexturedScene& scene,
                        const std::vector<glm::vec2>& uvs) {
  std::ostringstream out;
  out.precision(17);  // round trips the double 1 - t', and so t' (a float)
  out << "# " << scene.name << ": " << scene.faces.size() << " faces, retextured\n";
  for (const glm::vec3& p : scene.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const glm::vec2& uv : uvs) out << "vt " << uv.x << ' ' << 1.0 - double{uv.y} << '\n';
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    out << "g face_" << f << '\n';
    const TexturedFace& face = scene.faces[f];
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      out << 'f';
      for (uint32_t k = 0; k < 3; ++k) {
        const uint32_t v = scene.indices[t + k] + 1;
        out << ' ' << v << '/' << v;
      }
      out << '\n';
    }
  }
  writeFileAtomically(path, out.str());
}

void writeRetextureLayout(const std::filesystem::path& path, const TexturedScene& scene,
                          const Retexturing& layout, const LayoutSettings& settings) {
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  ordered_json images = ordered_json::array();
  for (const TextureArea& area : layout.areas) {
    const std::filesystem::path image =
        std::filesystem::absolute(scene.textures[area.texture].file);
    images.push_back({{"file", image.lexically_relative(folder).generic_string()},
                      {"x", area.x},
                      {"y", area.y},
                      {"width", area.width},
                      {"height", area.height},
                      {"source_x", area.sourceX},
                      {"source_y", area.sourceY}});
  }
  const ordered_json json = {{"page_size", layout.pageSize},
                             {"border", settings.border},
                             {"side", layout.side},
                             {"images", images}};
  writeFileAtomically(path, json.dump(1) + "\n");
}

void writeViewpointTour(const std::filesystem::path& path, const TexturedScene& scene) {
  constexpr int kFramesPerKeyframe = 24;
  ordered_json keyframes = ordered_json::array();
  const std::vector<Camera> views = coherenceViews(scene);
  for (size_t k = 0; k < views.size(); ++k) {
    const Camera& view = views[k];
    keyframes.push_back({{"frame", static_cast<int>(k) * kFramesPerKeyframe},
                         {"position", {view.position.x, view.position.y, view.position.z}},
                         {"target", {view.target.x, view.target.y, view.target.z}},
                         {"fov", view.fovYDegrees}});
  }
  writeFileAtomically(path, ordered_json{{"keyframes", keyframes}}.dump(1) + "\n");
}

void writeRetextureReport(const std::filesystem::path& path, const TexturedScene& scene,
                          const RetextureResult& result, const RetextureOptions& options) {
  uint64_t triangles = 0;
  for (const TexturedFace& face : scene.faces) triangles += face.indexCount / 3;
  uint32_t missing = 0;
  ordered_json textures = ordered_json::array();
  for (const SourceTexture& texture : scene.textures) {
    missing += texture.missing ? 1 : 0;
    textures.push_back({{"name", texture.name},
                        {"width", texture.width},
                        {"height", texture.height},
                        {"missing", texture.missing},
                        {"found_as", texture.foundAs}});
  }
  ordered_json viewpoints = ordered_json::array();
  for (const Camera& camera : scene.viewpoints) {
    std::ostringstream text;
    text.precision(9);
    text << camera.position.x << ',' << camera.position.y << ',' << camera.position.z << ':'
         << camera.target.x << ',' << camera.target.y << ',' << camera.target.z << ':'
         << camera.fovYDegrees;
    viewpoints.push_back(text.str());
  }
  const SkippedFaces& skipped = scene.skipped;
  const ordered_json json = {
      {"scene", scene.name},
      {"faces", scene.faces.size()},
      {"patch_faces", scene.patchFaces},
      {"surfaces_split_into_pieces", scene.splitSurfaces},
      {"triangles", triangles},
      {"textures", scene.textures.size()},
      {"missing_textures", missing},
      {"skipped_faces",
       {{"flare", skipped.flare},
        {"sky", skipped.sky},
        {"nodraw", skipped.noDraw},
        {"fog", skipped.fog},
        {"unknown_type", skipped.unknownType},
        {"not_finite", skipped.notFinite},
        {"degenerate", skipped.degenerate}}},
      {"page_size", options.pageSize},
      {"chosen_method", options.method},
      {"baseline", methodJson(result.baseline)},
      {"charts", methodJson(result.charts)},
      {"viewpoints", viewpoints},  // as `vt render --camera` takes them
      {"texture_list", textures},
      {"warnings", scene.warnings},
  };
  writeFileAtomically(path, json.dump(1) + "\n");
}

}  // namespace vt
