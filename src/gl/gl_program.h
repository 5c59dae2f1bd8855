#pragma once
// A linked GL program from vertex and fragment source (RAII). Compile and link errors throw
// std::runtime_error with the driver's log.

#include <epoxy/gl.h>

#include <string>

namespace vt {

class GlProgram {
 public:
  GlProgram(const std::string& vertexSource, const std::string& fragmentSource);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return program_; }
  GLint uniform(const char* name) const { return glGetUniformLocation(program_, name); }

 private:
  GLuint program_ = 0;
};

}  // namespace vt
