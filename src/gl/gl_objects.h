#pragma once
// Owners of OpenGL objects (RAII): each holds one name, made by the DSA create call and deleted
// when the owner goes, so a renderer frees nothing by hand. Movable, not copyable; making and
// deleting need the context the object belongs to current.

#include <epoxy/gl.h>

#include <utility>

namespace vt {

// One object of type Handle; Delete frees it. A default-constructed owner holds none.
template <class Handle, void (*Delete)(Handle)>
class GlObject {
 public:
  GlObject() = default;
  explicit GlObject(Handle handle) : handle_(handle) {}
  ~GlObject() { reset(); }
  GlObject(GlObject&& other) noexcept : handle_(std::exchange(other.handle_, Handle{})) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, Handle{});
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != Handle{}; }
  // Deletes the object now; the owner then holds none.
  void reset() {
    if (handle_ != Handle{}) Delete(std::exchange(handle_, Handle{}));
  }

 private:
  Handle handle_{};
};

namespace gl_delete {
// Function pointers, not epoxy's dispatch macros, so that they can be template arguments.
inline void texture(GLuint name) { glDeleteTextures(1, &name); }
inline void buffer(GLuint name) { glDeleteBuffers(1, &name); }
inline void framebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }
inline void vertexArray(GLuint name) { glDeleteVertexArrays(1, &name); }
inline void sync(GLsync fence) { glDeleteSync(fence); }
}  // namespace gl_delete

using GlTexture = GlObject<GLuint, gl_delete::texture>;
using GlBuffer = GlObject<GLuint, gl_delete::buffer>;
using GlFramebuffer = GlObject<GLuint, gl_delete::framebuffer>;
using GlVertexArray = GlObject<GLuint, gl_delete::vertexArray>;
using GlFence = GlObject<GLsync, gl_delete::sync>;

inline GlTexture createTexture(GLenum target) {
  GLuint name = 0;
  glCreateTextures(target, 1, &name);
  return GlTexture(name);
}

inline GlBuffer createBuffer() {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  return GlBuffer(name);
}

inline GlFramebuffer createFramebuffer() {
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  return GlFramebuffer(name);
}

inline GlVertexArray createVertexArray() {
  GLuint name = 0;
  glCreateVertexArrays(1, &name);
  return GlVertexArray(name);
}

// A fence after the commands issued so far.
inline GlFence insertFence() { return GlFence(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0)); }

}  // namespace vt
