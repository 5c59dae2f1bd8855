// The shared shader logic is GLSL too: the driver compiles and links the fragment shader that
// includes it verbatim (on llvmpipe in CI).

#include "gl/virtual_texture_program.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include "gl/headless_context.h"

namespace vt {
namespace {

// Compiles one stage; returns the shader, or 0 with the driver's log in `log`.
GLuint compile(GLenum stage, const std::string& source, std::string& log) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0, length = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  log.assign(static_cast<size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  if (!ok) {
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

TEST(VirtualTextureProgram, SharedLogicCompilesAndLinksAsGlsl) {
  const HeadlessContext context;
  std::string log;
  const GLuint vertex = compile(GL_VERTEX_SHADER, virtualTextureVertexSource(), log);
  ASSERT_NE(vertex, 0u) << log;
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, virtualTextureFragmentSource(), log);
  ASSERT_NE(fragment, 0u) << log;
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  EXPECT_TRUE(linked);
  // The parameters struct reaches the program as uniforms of the shared types.
  EXPECT_GE(glGetUniformLocation(program, "uVt.pageSize"), 0);
  EXPECT_GE(glGetUniformLocation(program, "uVt.cacheSize"), 0);
  glDeleteProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
}

}  // namespace
}  // namespace vt
