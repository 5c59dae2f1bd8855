#include "probes/function_sweeps.h"

#include <epoxy/gl.h>

#include <stdexcept>

#include "gl/gl_program.h"

namespace vt::calibrate {
namespace {

// A triangle covering the viewport, from gl_VertexID alone (the clipper cuts it).
const char* kSweepVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

std::string sweepFragment(const FunctionSweep& sweep) {
  return "#version 450 core\n"
         "layout(location = 0) uniform uint uFirst;\n"
         "layout(location = 0) out uint outBits;\n"
         "void main() {\n"
         "  uint i = uint(gl_FragCoord.y) * " +
         std::to_string(kSweepWidth) +
         "u + uint(gl_FragCoord.x);\n"
         "  precise float x = uintBitsToFloat(uFirst + i);\n"
         "  precise float result = " +
         sweep.expression +
         ";\n"
         "  outBits = floatBitsToUint(result);\n"
         "}\n";
}

}  // namespace

const std::vector<FunctionSweep>& functionSweeps() {
  static const std::vector<FunctionSweep> sweeps = {
      {"log2", "log2(x)", 0x3f000000u, uint32_t{1} << 24},  // [0.5, 2)
      {"sqrt", "sqrt(x)", 0x3f800000u, uint32_t{1} << 24},  // [1, 4)
  };
  return sweeps;
}

std::vector<uint32_t> drawFunctionSweepHere(const FunctionSweep& sweep) {
  if (sweep.count == 0 || sweep.count % kSweepWidth != 0 || sweep.count > kMaxSweepCount ||
      uint64_t{sweep.first} + sweep.count > (uint64_t{1} << 32))
    throw std::invalid_argument("function sweep " + sweep.name + ": not whole rows of inputs");
  const auto width = static_cast<GLsizei>(kSweepWidth);
  const auto height = static_cast<GLsizei>(sweep.count / kSweepWidth);
  const GlProgram program(kSweepVertex, sweepFragment(sweep));
  GLuint target = 0, framebuffer = 0, array = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &target);
  glTextureStorage2D(target, 1, GL_R32UI, width, height);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
  glCreateVertexArrays(1, &array);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_DITHER);
  glUseProgram(program.id());
  glProgramUniform1ui(program.id(), 0, sweep.first);
  glBindVertexArray(array);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<uint32_t> bits(sweep.count);
  glGetTextureImage(target, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                    static_cast<GLsizei>(bits.size() * sizeof(uint32_t)), bits.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glDeleteVertexArrays(1, &array);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &target);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw std::runtime_error("function sweep " + sweep.name + " failed: GL error " +
                             std::to_string(error));
  return bits;
}

}  // namespace vt::calibrate
