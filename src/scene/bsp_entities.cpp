#include "scene/bsp_entities.h"

#include <optional>

#include "common/error.h"

namespace vt {
namespace {

// Splits the entity text into '{', '}' and quoted strings, counting lines (from 1) for errors. As
// in Quake 3's COM_Parse, a string may span lines and has no escapes, and "//" starts a comment.
class EntityTokenizer {
 public:
  struct Token {
    char kind = 0;  // '{', '}' or '"' for a string
    std::string text;
    int line = 1;
  };

  EntityTokenizer(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  std::optional<Token> next() {
    skipSpaceAndComments();
    if (position_ == text_.size()) return std::nullopt;
    const char c = text_[position_];
    if (c == '{' || c == '}') {
      ++position_;
      return Token{c, {}, line_};
    }
    if (c != '"') fail(line_, std::string("unexpected character '") + c + "' outside a string");
    const int startLine = line_;
    const size_t close = text_.find('"', position_ + 1);
    if (close == std::string_view::npos) fail(startLine, "unterminated string");
    Token token{'"', std::string(text_.substr(position_ + 1, close - position_ - 1)), startLine};
    for (const char s : token.text) line_ += s == '\n';
    position_ = close + 1;
    return token;
  }

  [[noreturn]] void fail(int line, const std::string& problem) const {
    throw InputError(name_, "entities line " + std::to_string(line) + ": " + problem);
  }

 private:
  void skipSpaceAndComments() {
    while (position_ < text_.size()) {
      const char c = text_[position_];
      if (c == '/' && text_.substr(position_, 2) == "//") {
        while (position_ < text_.size() && text_[position_] != '\n') ++position_;
      } else if (static_cast<unsigned char>(c) <= ' ') {
        line_ += c == '\n';
        ++position_;
      } else {
        return;
      }
    }
  }

  std::string_view text_;
  const std::string& name_;
  size_t position_ = 0;
  int line_ = 1;
};

}  // namespace

// A key given twice keeps its last value.
std::vector<BspEntity> parseEntities(std::string_view text, const std::string& name) {
  EntityTokenizer tokens(text, name);
  std::vector<BspEntity> entities;
  while (const auto open = tokens.next()) {
    if (open->kind != '{')
      tokens.fail(open->line, open->kind == '}'
                                  ? "'}' without a matching '{'"
                                  : "string \"" + open->text + "\" outside an entity");
    BspEntity entity;
    while (true) {
      const auto key = tokens.next();
      if (!key) tokens.fail(open->line, "the entity opened here is never closed");
      if (key->kind == '}') break;
      if (key->kind == '{') tokens.fail(key->line, "'{' inside an entity");
      const auto value = tokens.next();
      if (!value) tokens.fail(open->line, "the entity opened here is never closed");
      if (value->kind != '"') tokens.fail(value->line, "key \"" + key->text + "\" has no value");
      entity[key->text] = value->text;
    }
    entities.push_back(std::move(entity));
  }
  return entities;
}

}  // namespace vt
