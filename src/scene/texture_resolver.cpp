#include "scene/texture_resolver.h"

#include <string>

#include "common/resource_limits.h"
#include "scene/shader_script.h"

namespace vt {
namespace {

// "textures/x/y.tga" -> "textures/x/y"; a dot in a folder's name is not an extension.
std::string_view withoutExtension(std::string_view name) {
  const size_t dot = name.rfind('.'), slash = name.find_last_of("/\\");
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash))
    return name;
  return name.substr(0, dot);
}

// The archive entry of `<name>.tga`, else of `<name>.jpg`, whatever extension `name` carries.
std::optional<std::string> findImage(const PackageFiles& files, std::string_view name) {
  const std::string stem(withoutExtension(name));
  for (const char* extension : {".tga", ".jpg"}) {
    if (auto file = files.find(stem + extension)) return file;
  }
  return std::nullopt;
}

}  // namespace

TextureResolver::TextureResolver(const PackageFiles& files) : files_(files) {
  // list() returns the scripts in name order; a later script's definition replaces an earlier
  // one, as the game reads its scripts in reverse name order and takes the first it finds.
  for (const std::string& script : files.list("scripts/", ".shader")) {
    const std::vector<uint8_t> bytes = files.read(script, kMaxShaderScriptBytes);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    for (ShaderDefinition& definition : parseShaderScript(text, files.describe(script))) {
      shaders_.insert_or_assign(
          packageNameKey(definition.name),
          ScriptImages{std::move(definition.firstMapImage), std::move(definition.editorImage)});
    }
  }
}

std::optional<ResolvedTexture> TextureResolver::resolve(std::string_view shaderName) const {
  using Via = ResolvedTexture::Via;
  if (auto file = findImage(files_, shaderName)) return ResolvedTexture{*file, Via::kImage};
  // The game looks shaders up by the name without its extension too (R_FindShader).
  const auto shader = shaders_.find(packageNameKey(withoutExtension(shaderName)));
  if (shader == shaders_.end()) return std::nullopt;
  const ScriptImages& images = shader->second;
  if (images.firstMapImage) {
    if (auto file = findImage(files_, *images.firstMapImage))
      return ResolvedTexture{*file, Via::kShaderStage};
  }
  if (images.editorImage) {
    if (auto file = findImage(files_, *images.editorImage))
      return ResolvedTexture{*file, Via::kEditorImage};
  }
  return std::nullopt;
}

}  // namespace vt
