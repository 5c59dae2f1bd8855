#pragma once
// Finds the image a Quake 3 map's shader name stands for. Names carry no extension (or the wrong
// one): the image is `<name>.tga`, else `<name>.jpg`, compared without regard to case. A name with
// no such image that a shader script defines resolves to the script's first map/clampmap stage,
// else its qer_editorimage, whose names are tried the same way (scripts name `x.tga` where only
// `x.jpg` exists). When a shader is defined in several scripts the last script in name order wins,
// as in the game.
// A stage image that no archive holds falls back to the editor image; a name's extension is
// dropped before the shader look-up, as the game's R_FindShader does.

#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "scene/package_files.h"

namespace vt {

struct ResolvedTexture {
  std::string file;  // the archive entry holding the image
  enum class Via { kImage, kShaderStage, kEditorImage } via = Via::kImage;
};

class TextureResolver {
 public:
  // Reads and parses every scripts/*.shader of `files` (an unreadable script is an InputError).
  explicit TextureResolver(const PackageFiles& files);

  // The image for `shaderName`, or nothing when neither an image nor a script provides one.
  std::optional<ResolvedTexture> resolve(std::string_view shaderName) const;

 private:
  const PackageFiles& files_;
  struct ScriptImages {
    std::optional<std::string> firstMapImage, editorImage;
  };
  std::unordered_map<std::string, ScriptImages> shaders_;  // by lower-cased shader name
};

}  // namespace vt
