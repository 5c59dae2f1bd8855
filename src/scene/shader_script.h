#pragma once
// Quake 3 shader scripts (scripts/*.shader): only what retexturing needs from each definition, the
// image of its first `map` or `clampmap` stage (not $lightmap or $whiteimage) and its
// `qer_editorimage`.
//
// Syntax: `name { directive... { stage directive... } ... }`, tokens separated by white space,
// "quoted tokens", // and /* */ comments; keywords are case-insensitive.
//
// Tokens follow Quake 3's COM_ParseExt, so a script reads as the game reads it: a token is a run of
// characters above ' ', a comment or a quote starts only where a token would, and a directive's
// arguments are the tokens after its keyword on the same line. The first stage with a `map` or
// `clampmap` of a real image counts: built-in images (`$lightmap`, `$whiteimage`, any `$...`, and
// the engine's `*white`) are skipped, `animMap` is not a map stage. The first `qer_editorimage` of
// the outer block counts; every other directive is ignored. A definition that does not close, a
// '}' with nothing open, a stage block inside a stage, a name without '{' after it, or a quote
// that does not close is an InputError naming the line.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

struct ShaderDefinition {
  std::string name;                          // as written, e.g. "textures/sfx/flame1"
  std::optional<std::string> firstMapImage;  // e.g. "textures/sfx/flame1.tga"
  std::optional<std::string> editorImage;
};

// Parses one script. Unbalanced braces or a stage outside a definition are an InputError naming
// `name` and the line.
std::vector<ShaderDefinition> parseShaderScript(std::string_view text, const std::string& name);

}  // namespace vt
