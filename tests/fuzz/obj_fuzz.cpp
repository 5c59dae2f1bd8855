// Fuzz target: OBJ scenes with their MTL materials (scene/obj_scene.h) and OBJ meshes
// (scene/obj_mesh.h), both through tinyobjloader.

#include <filesystem>
#include <string>
#include <string_view>

#include "fuzz/fuzz_targets.h"
#include "scene/obj_mesh.h"
#include "scene/obj_scene.h"

namespace vt::fuzz {

void objScene(Input input) {
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  const std::string separator = std::string("\n") + kMtlSeparator + "\n";
  const size_t split = text.find(separator);
  ObjSceneText source;
  source.path = "/nonexistent/vt-fuzz/scene.obj";
  source.obj = std::string(text.substr(0, split));
  const std::string mtl =
      split == std::string_view::npos ? "" : std::string(text.substr(split + separator.size()));
  for (const std::string& library : materialLibraryNames(source.obj))
    source.materialLibraries.try_emplace(library, mtl);
  // Images are never opened: a name containing "bad" is unreadable, any other is 64 x 64 RGB.
  source.imageHeader = [](const std::filesystem::path& image) -> std::optional<ImageHeader> {
    if (image.string().find("bad") != std::string::npos) return std::nullopt;
    return ImageHeader{64, 64, 3};
  };
  // Only the checker image is written, once, here.
  const std::filesystem::path images = std::filesystem::temp_directory_path() / "vt-fuzz-images";
  try {
    loadObjScene(source, images);
  } catch (const InputError&) {
  }
  parseObjMesh(source.obj, source.path);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::objScene)
