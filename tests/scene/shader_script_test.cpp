// The shader script parser on script text. The TextureResolver, which needs archives, is tested in
// package_files_test.cpp.

#include "scene/shader_script.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/error.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

TEST(ShaderScript, ReadsFirstMapStageAndEditorImageThroughComments) {
  const std::vector<ShaderDefinition> shaders = parseShaderScript(R"(
// a line comment { with a brace }
textures/sfx/flame1   /* a block comment
   that spans { lines */
{
  qer_editorimage "textures/sfx/flame1_ed.tga"   // quoted, then a comment
  surfaceparm nomarks
  q3map_surfacelight 1000 cull none
  {
    map $lightmap
    rgbGen identity
  }
  {
    map textures/sfx/flame1.tga // the first real stage
    blendFunc GL_DST_COLOR GL_ZERO
  }
  {
    map textures/sfx/flame2.tga
  }
}

textures/base/plain
{
}
)",
                                                                  "sfx.shader");
  ASSERT_EQ(shaders.size(), 2u);
  EXPECT_EQ(shaders[0].name, "textures/sfx/flame1");
  EXPECT_EQ(shaders[0].firstMapImage, "textures/sfx/flame1.tga");
  EXPECT_EQ(shaders[0].editorImage, "textures/sfx/flame1_ed.tga");
  EXPECT_EQ(shaders[1].name, "textures/base/plain");
  EXPECT_EQ(shaders[1].firstMapImage, std::nullopt);
  EXPECT_EQ(shaders[1].editorImage, std::nullopt);
}

TEST(ShaderScript, ClampMapCountsAnimMapDoesNotAndKeywordsIgnoreCase) {
  const auto shaders = parseShaderScript(
      "Textures/Sfx/Pulse {\r\n"
      "  QER_EditorImage textures/sfx/pulse_ed\r\n"
      "  { animMap 4 textures/sfx/p1.tga textures/sfx/p2.tga }\r\n"
      "  { ClampMap \"textures/sfx/pulse.tga\" }\r\n"
      "}\r\n",
      "pulse.shader");
  ASSERT_EQ(shaders.size(), 1u);
  EXPECT_EQ(shaders[0].name, "Textures/Sfx/Pulse");
  EXPECT_EQ(shaders[0].firstMapImage, "textures/sfx/pulse.tga");
  EXPECT_EQ(shaders[0].editorImage, "textures/sfx/pulse_ed");
}

TEST(ShaderScript, SkipsTheEnginesOwnImages) {
  const auto shaders = parseShaderScript(R"(
textures/sfx/glass
{
  { map $lightmap }
  { clampmap $whiteimage }
  { map $anything }
  { map *white }
  qer_editorimage textures/sfx/glass_ed.jpg
})",
                                         "glass.shader");
  ASSERT_EQ(shaders.size(), 1u);
  EXPECT_EQ(shaders[0].firstMapImage, std::nullopt);
  EXPECT_EQ(shaders[0].editorImage, "textures/sfx/glass_ed.jpg");
}

TEST(ShaderScript, ArgumentsStayOnTheirDirectivesLine) {
  // `map` alone on its line has no image: the next line is a directive of its own, as in the game.
  const auto shaders = parseShaderScript(
      "textures/a/b\n{\n  {\n    map\n    textures/a/not_an_argument.tga\n  }\n"
      "  { map textures/a/b.tga }\n}\n",
      "lines.shader");
  ASSERT_EQ(shaders.size(), 1u);
  EXPECT_EQ(shaders[0].firstMapImage, "textures/a/b.tga");
}

TEST(ShaderScript, OuterDirectivesOtherThanTheEditorImageAreIgnored) {
  // `map` outside a stage is not a stage; only the first qer_editorimage counts.
  const auto shaders = parseShaderScript(
      "textures/a/c { map textures/a/outer.tga\n qer_editorimage textures/a/first.tga\n"
      " qer_editorimage textures/a/second.tga\n }",
      "outer.shader");
  ASSERT_EQ(shaders.size(), 1u);
  EXPECT_EQ(shaders[0].firstMapImage, std::nullopt);
  EXPECT_EQ(shaders[0].editorImage, "textures/a/first.tga");
}

TEST(ShaderScript, EmptyScriptHasNoDefinitions) {
  EXPECT_TRUE(parseShaderScript("  // nothing\n/* at all */\n", "empty.shader").empty());
}

// The parse of `text` fails with a message naming the script and `line`.
void expectRejected(const std::string& text, int line, const std::string& problem) {
  try {
    parseShaderScript(text, "scripts/broken.shader");
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "scripts/broken.shader");
    EXPECT_THAT(error.what(),
                AllOf(HasSubstr("scripts/broken.shader"),
                      HasSubstr("line " + std::to_string(line) + ":"), HasSubstr(problem)));
  }
}

TEST(ShaderScript, RejectsUnbalancedBracesWithTheLine) {
  expectRejected("textures/a/ok\n{\n}\ntextures/a/open\n{\n  { map x.tga }\n", 5,
                 "'textures/a/open'");
  expectRejected("textures/a/b\n{\n  {\n    map x.tga\n", 3, "stage of 'textures/a/b'");
  // The stage's '}' is the definition's missing one.
  expectRejected("textures/a/b\n{\n  {\n    map x.tga\n}\n", 2, "'textures/a/b'");
  expectRejected("textures/a/b\n{\n}\n}\n", 4, "closes nothing");
  expectRejected("textures/a/b\n{\n}\n{\n map x.tga\n}\n", 4, "outside a definition");
  expectRejected("textures/a/b { { { map x.tga } } }", 1, "inside a stage");
  expectRejected("textures/a/b\n\nmap x.tga\n", 1, "not followed by '{'");
  expectRejected("textures/a/b\n{\n qer_editorimage \"x.tga\n}\n", 3, "quoted");
  expectRejected("textures/a/b\n{\n}\n/* never closed\n", 4, "comment");
}

}  // namespace
}  // namespace vt
