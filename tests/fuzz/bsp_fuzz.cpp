// Fuzz target: Quake 3 maps (scene/bsp_file.h) and the scene made of them (scene/quake3_scene.h).

#include <map>
#include <string>

#include "fuzz/fuzz_targets.h"
#include "scene/bsp_file.h"
#include "scene/quake3_scene.h"

namespace vt::fuzz {

void bspMap(Input input) {
  const std::string source = "fuzz.pk3:maps/fuzz.bsp";
  const BspFile bsp = parseBsp(input, source);
  // One placeholder texture per shader, as loadQuake3Map makes one per shader used.
  std::map<int32_t, uint32_t> byShader;
  const auto placeholder = [&](int32_t shader, const std::string& name, TexturedScene& scene) {
    const auto [found, added] =
        byShader.try_emplace(shader, static_cast<uint32_t>(scene.textures.size()));
    if (added) {
      SourceTexture texture;
      texture.name = name;
      texture.width = texture.height = 64;
      scene.textures.push_back(texture);
    }
    return found->second;
  };
  quake3Scene(bsp, source, placeholder);
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::bspMap)
