#include "scene/shader_script.h"

#include <algorithm>
#include <span>

#include "common/error.h"

namespace vt {
namespace {

struct Token {
  std::string text;
  int line = 0;
  bool quoted = false;

  // A quoted "{" is text, as in the game.
  bool is(char brace) const { return !quoted && text.size() == 1 && text[0] == brace; }
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  const auto lower = [](char c) {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  };
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [&](char x, char y) { return lower(x) == lower(y); });
}

class ScriptParser {
 public:
  ScriptParser(std::string_view text, const std::string& name) : name_(name) { tokenize(text); }

  std::vector<ShaderDefinition> definitions() {
    std::vector<ShaderDefinition> definitions;
    while (at_ < tokens_.size()) definitions.push_back(definition());
    return definitions;
  }

 private:
  InputError error(int line, const std::string& problem) const {
    return InputError(name_, "line " + std::to_string(line) + ": " + problem);
  }

  // Splits the text as Quake 3's COM_ParseExt does: white space is every character up to ' ', and
  // comments and quotes are recognised only where a token would start.
  void tokenize(std::string_view text) {
    int line = 1;
    size_t i = 0;
    const auto startsWith = [&](std::string_view s) { return text.substr(i).starts_with(s); };
    while (i < text.size()) {
      const char c = text[i];
      if (static_cast<unsigned char>(c) <= ' ') {
        if (c == '\n') ++line;
        ++i;
      } else if (startsWith("//")) {
        i = std::min(text.find('\n', i), text.size());
      } else if (startsWith("/*")) {
        const size_t end = text.find("*/", i + 2);
        if (end == std::string_view::npos) throw error(line, "a /* comment does not close");
        line += static_cast<int>(std::count(text.begin() + i, text.begin() + end, '\n'));
        i = end + 2;
      } else if (c == '"') {
        const size_t end = text.find('"', i + 1);
        if (end == std::string_view::npos) throw error(line, "a quoted token does not close");
        tokens_.push_back({std::string(text.substr(i + 1, end - i - 1)), line, true});
        line += static_cast<int>(std::count(text.begin() + i, text.begin() + end, '\n'));
        i = end + 1;
      } else {
        size_t end = i;
        while (end < text.size() && static_cast<unsigned char>(text[end]) > ' ') ++end;
        tokens_.push_back({std::string(text.substr(i, end - i)), line, false});
        i = end;
      }
    }
  }

  // `name { directive... { stage... }... }`
  ShaderDefinition definition() {
    const Token& name = tokens_[at_++];
    if (name.is('{')) throw error(name.line, "a '{' block outside a definition (no shader name)");
    if (name.is('}')) throw error(name.line, "a '}' that closes nothing");
    if (at_ == tokens_.size() || !tokens_[at_].is('{'))
      throw error(name.line, "shader '" + name.text + "' is not followed by '{'");
    const int opened = tokens_[at_++].line;
    ShaderDefinition definition{name.text, std::nullopt, std::nullopt};
    while (at_ < tokens_.size()) {
      if (tokens_[at_].is('}')) {
        ++at_;
        return definition;
      }
      if (tokens_[at_].is('{')) {
        stage(definition);
        continue;
      }
      const auto [keyword, arguments] = directive();
      if (equalsIgnoringCase(keyword, "qer_editorimage") && !arguments.empty() &&
          !definition.editorImage)
        definition.editorImage = arguments.front().text;
    }
    throw error(opened, "the definition of '" + name.text + "' opened here does not close");
  }

  // `{ stage directive... }`, its opening brace at `at_`.
  void stage(ShaderDefinition& definition) {
    const int opened = tokens_[at_++].line;
    while (at_ < tokens_.size()) {
      if (tokens_[at_].is('}')) {
        ++at_;
        return;
      }
      if (tokens_[at_].is('{'))
        throw error(tokens_[at_].line, "a block inside a stage of '" + definition.name + "'");
      const auto [keyword, arguments] = directive();
      const bool mapStage =
          equalsIgnoringCase(keyword, "map") || equalsIgnoringCase(keyword, "clampmap");
      if (mapStage && !arguments.empty() && isImageFile(arguments.front().text) &&
          !definition.firstMapImage)
        definition.firstMapImage = arguments.front().text;
    }
    throw error(opened, "a stage of '" + definition.name + "' opened here does not close");
  }

  // A keyword and the tokens after it on its line, braces excluded.
  struct Directive {
    std::string_view keyword;
    std::span<const Token> arguments;
  };
  Directive directive() {
    const size_t keyword = at_++;
    while (at_ < tokens_.size() && tokens_[at_].line == tokens_[keyword].line &&
           !tokens_[at_].is('{') && !tokens_[at_].is('}'))
      ++at_;
    return {tokens_[keyword].text,
            std::span<const Token>(tokens_).subspan(keyword + 1, at_ - keyword - 1)};
  }

  // `$lightmap`, `$whiteimage` and `*white` are the engine's own images, not files.
  static bool isImageFile(std::string_view image) {
    return !image.empty() && image.front() != '$' && image.front() != '*';
  }

  const std::string& name_;
  std::vector<Token> tokens_;
  size_t at_ = 0;
};

}  // namespace

std::vector<ShaderDefinition> parseShaderScript(std::string_view text, const std::string& name) {
  return ScriptParser(text, name).definitions();
}

}  // namespace vt
