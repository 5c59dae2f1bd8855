#include "probes/probe_draws.h"

#include <epoxy/gl.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <random>
#include <stdexcept>

#include "common/random_draws.h"
#include "gl/gl_program.h"

namespace vt::calibrate {
namespace {

// GL names released when the draw is done, also when it throws.
struct Names {
  std::vector<GLuint> textures, framebuffers, buffers, arrays;
  ~Names() {
    if (!textures.empty()) glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
    if (!framebuffers.empty())
      glDeleteFramebuffers(static_cast<GLsizei>(framebuffers.size()), framebuffers.data());
    if (!buffers.empty()) glDeleteBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    if (!arrays.empty()) glDeleteVertexArrays(static_cast<GLsizei>(arrays.size()), arrays.data());
  }
  GLuint texture(GLenum format, int width, int height) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    textures.push_back(name);
    glTextureStorage2D(name, 1, format, width, height);
    return name;
  }
  GLuint framebuffer() {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    framebuffers.push_back(name);
    return name;
  }
};

void requireNoError(const char* what) {
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw std::runtime_error(std::string("calibration draw (") + what + ") failed: GL error " +
                             std::to_string(error));
}

// A triangle covering the viewport, from gl_VertexID alone (the clipper cuts it).
const char* kFullScreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// Two triangles that cover the viewport exactly: corners on the clip planes, none outside.
const char* kFullScreenQuadVertex = R"(#version 450 core
void main() {
  const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1),
                                 vec2(-1, 1));
  gl_Position = vec4(corners[gl_VertexID], 0.0, 1.0);
}
)";

std::string fragmentSource(const ShaderProbe& probe, const char* outputType) {
  return std::string("#version 450 core\n") +
         "layout(binding = 0) uniform sampler2D uInputs;\n"
         "layout(binding = 1) uniform sampler2D uTexture;\n"
         "layout(location = 0) out " +
         outputType +
         " outResult;\n"
         "void main() {\n"
         "  vec4 x = texelFetch(uInputs, ivec2(gl_FragCoord.xy), 0);\n"
         "  precise vec4 result;\n  " +
         probe.body + "\n  outResult = result;\n}\n";
}

std::string sweepFragment(const FunctionSweep& sweep) {
  const bool depth = sweep.target == SweepTarget::kDepth24;
  return std::string("#version 450 core\n") +
         "layout(location = 0) uniform uint uFirst;\n" +
         (depth ? "" : "layout(location = 0) out uint outBits;\n") +
         "void main() {\n"
         "  uint i = uint(gl_FragCoord.y) * " +
         std::to_string(kSweepWidth) +
         "u + uint(gl_FragCoord.x);\n"
         "  precise float x = uintBitsToFloat(uFirst + i);\n"
         "  precise float result = " +
         sweep.expression + ";\n" +
         (depth ? "  gl_FragDepth = result;\n" : "  outBits = floatBitsToUint(result);\n") +
         "}\n";
}

// Draws the probe into a `format` target and reads it back as `readFormat`/`readType`.
template <class Texel>
std::vector<Texel> drawProbe(const ShaderProbe& probe, GLenum format, GLenum readFormat,
                             GLenum readType, const char* outputType) {
  if (probe.width < 1 || probe.inputs.empty() || probe.inputs.size() % probe.width != 0)
    throw std::invalid_argument("calibration probe: inputs are not whole rows");
  const int width = probe.width, height = static_cast<int>(probe.inputs.size()) / probe.width;
  const GlProgram program(probe.clipped ? kFullScreenVertex : kFullScreenQuadVertex,
                          fragmentSource(probe, outputType));
  Names names;
  const GLuint inputs = names.texture(GL_RGBA32F, width, height);
  glTextureSubImage2D(inputs, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, probe.inputs.data());
  glBindTextureUnit(0, inputs);
  if (!probe.texels.empty() || !probe.blocks.empty()) {
    GLuint texture = 0;
    if (probe.blocks.empty()) {
      texture = names.texture(GL_RGBA8, probe.textureSize.x, probe.textureSize.y);
      glTextureSubImage2D(texture, 0, 0, 0, probe.textureSize.x, probe.textureSize.y, GL_RGBA,
                          GL_UNSIGNED_BYTE, probe.texels.data());
    } else {
      const GLenum format = probe.blockFormat == PixelFormat::kBc1
                                ? GL_COMPRESSED_RGB_S3TC_DXT1_EXT
                                : GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
      texture = names.texture(format, probe.textureSize.x, probe.textureSize.y);
      glCompressedTextureSubImage2D(texture, 0, 0, 0, probe.textureSize.x, probe.textureSize.y,
                                    format, static_cast<GLsizei>(probe.blocks.size()),
                                    probe.blocks.data());
    }
    const GLint filter = probe.linear ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTextureUnit(1, texture);
  }
  const GLuint target = names.texture(format, width, height);
  const GLuint framebuffer = names.framebuffer();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
  GLuint array = 0;
  glCreateVertexArrays(1, &array);
  names.arrays.push_back(array);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_DITHER);
  glUseProgram(program.id());
  glBindVertexArray(array);
  glDrawArrays(GL_TRIANGLES, 0, probe.clipped ? 3 : 6);
  std::vector<Texel> result(probe.inputs.size());
  glGetTextureImage(target, 0, readFormat, readType,
                    static_cast<GLsizei>(result.size() * sizeof(Texel)), result.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  requireNoError("shader probe");
  return result;
}

thread_local ProbeDrawer* currentDrawer = nullptr;

std::string glString(GLenum name) {
  const GLubyte* text = glGetString(name);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace

UsingProbeDrawer::UsingProbeDrawer(ProbeDrawer& drawer) : previous_(currentDrawer) {
  currentDrawer = &drawer;
}
UsingProbeDrawer::~UsingProbeDrawer() { currentDrawer = previous_; }

std::vector<glm::vec4> drawShaderProbeHere(const ShaderProbe& probe) {
  return drawProbe<glm::vec4>(probe, GL_RGBA32F, GL_RGBA, GL_FLOAT, "vec4");
}

std::vector<glm::u8vec4> drawColourProbeHere(const ShaderProbe& probe) {
  return drawProbe<glm::u8vec4>(probe, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, "vec4");
}

std::vector<uint32_t> drawFunctionSweepHere(const FunctionSweep& sweep) {
  if (sweep.count == 0 || sweep.count % kSweepWidth != 0 || sweep.count > kMaxSweepCount ||
      uint64_t{sweep.first} + sweep.count > (uint64_t{1} << 32))
    throw std::invalid_argument("function sweep " + sweep.name + ": not whole rows of inputs");
  const auto width = static_cast<GLsizei>(kSweepWidth);
  const auto height = static_cast<GLsizei>(sweep.count / kSweepWidth);
  const GlProgram program(kFullScreenVertex, sweepFragment(sweep));
  const bool depth = sweep.target == SweepTarget::kDepth24;
  Names names;
  const GLuint target = names.texture(depth ? GL_DEPTH_COMPONENT24 : GL_R32UI, width, height);
  const GLuint framebuffer = names.framebuffer();
  glNamedFramebufferTexture(framebuffer, depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0,
                            target, 0);
  if (depth) glNamedFramebufferDrawBuffer(framebuffer, GL_NONE);
  GLuint array = 0;
  glCreateVertexArrays(1, &array);
  names.arrays.push_back(array);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  if (depth) {
    // Every fragment writes its value whatever the buffer held: GL_ALWAYS, depth writes on.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  glDisable(GL_DITHER);
  glUseProgram(program.id());
  glProgramUniform1ui(program.id(), 0, sweep.first);
  glBindVertexArray(array);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<uint32_t> bits(sweep.count);
  const auto bytes = static_cast<GLsizei>(bits.size() * sizeof(uint32_t));
  if (depth) {
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    // The stored integer in the top 24 bits of a 32-bit unorm (as readDepth reads Z24).
    glGetTextureImage(target, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, bytes, bits.data());
    for (uint32_t& b : bits) b >>= 8;
  } else {
    glGetTextureImage(target, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, bytes, bits.data());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  requireNoError("function sweep");
  return bits;
}

ProbeIdentity identityHere() {
  return {glString(GL_RENDERER), glString(GL_VERSION), glString(GL_VENDOR)};
}

namespace {

// No value a fit compares may be NaN or infinite: a comparison with NaN is false, so it would slip
// past every check of a bound and become the model. The calibration's probes are made so that every
// exact result is a finite number (shader probes: log2 and sqrt of positive inputs, products, lerps
// and texture reads of finite values; triangles: attributes and depth of finite vertices with
// w > 0 at every covered pixel), and GL 4.5 section 2.3.4 and GLSL 4.50 section 4.7.1 give
// operations on finite values a finite result within their precision. Anything else breaks a rule:
// the calibration stops with the probe and the value, and writes no model.
std::string valueText(float v) { return std::isnan(v) ? "NaN" : v > 0 ? "+infinity" : "-infinity"; }

[[noreturn]] void refuseValue(const std::string& probe, size_t at, const std::string& what,
                              float v) {
  throw std::runtime_error(
      "the implementation breaks a rule (GL 4.5 core, section 2.3.4; GLSL 4.50, section 4.7.1: "
      "operations on finite values give finite results): " +
      probe + " returned " + valueText(v) + " " + what + " " + std::to_string(at) +
      ", where the exact result is a finite number; no model written");
}

void refuseNonFinite(const ShaderProbe& probe, const std::vector<glm::vec4>& out) {
  for (size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(out[i][c]))
        refuseValue("the shader probe '" + probe.body + "'", i,
                    "in channel " + std::to_string(c) + " of sample", out[i][c]);
}

void refuseNonFinite(const RasterReadback& r, size_t triangles) {
  for (size_t i = 0; i < r.triangle.size(); ++i) {
    if (r.triangle[i] < 0) continue;  // uncovered: nothing was interpolated there
    const float values[] = {r.uv[i].x,          r.uv[i].y,          r.derivatives[i].x,
                            r.derivatives[i].y, r.derivatives[i].z, r.derivatives[i].w,
                            r.depth[i]};
    for (const float v : values)
      if (!std::isfinite(v))
        refuseValue("the triangle probe of " + std::to_string(triangles) + " triangles", i,
                    "as a texture coordinate, derivative or depth at covered pixel", v);
  }
}

}  // namespace

std::vector<glm::vec4> runShaderProbe(const ShaderProbe& probe) {
  std::vector<glm::vec4> out =
      currentDrawer ? currentDrawer->shader(probe) : drawShaderProbeHere(probe);
  refuseNonFinite(probe, out);
  return out;
}

std::vector<glm::u8vec4> runColourProbe(const ShaderProbe& probe) {
  return currentDrawer ? currentDrawer->colour(probe) : drawColourProbeHere(probe);
}

RasterReadback drawTriangles(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                             Interpolation interpolation) {
  RasterReadback r = currentDrawer ? currentDrawer->triangles(mesh, viewport, format, interpolation)
                                   : drawTrianglesHere(mesh, viewport, format, interpolation);
  refuseNonFinite(r, mesh.indices.size() / 3);
  return r;
}

bool holdsOptionalGroup(size_t draws) {
  return currentDrawer ? currentDrawer->holdsGroup(draws) : true;
}

ProbeIdentity probeIdentity() { return currentDrawer ? currentDrawer->identity() : identityHere(); }

std::optional<std::vector<uint32_t>> functionSweep(const FunctionSweep& sweep) {
  std::optional<std::vector<uint32_t>> bits =
      currentDrawer ? currentDrawer->sweep(sweep) : drawFunctionSweepHere(sweep);
  // A depth sweep stores 24-bit integers: a larger one is no Z24 value.
  if (sweep.target == SweepTarget::kDepth24) {
    for (size_t i = 0; bits && i < bits->size(); ++i)
      if ((*bits)[i] > 0xffffffu)
        throw std::runtime_error("the depth sweep " + sweep.name + " returned " +
                                 std::to_string((*bits)[i]) + " at input " + std::to_string(i) +
                                 ", which is no 24-bit depth value; no model written");
    return bits;
  }
  // The pack's functions have finite exact results over their intervals (function_sweeps.h).
  for (size_t i = 0; bits && i < bits->size(); ++i)
    if (const float v = std::bit_cast<float>((*bits)[i]); !std::isfinite(v))
      refuseValue("the sweep of " + sweep.expression + " over every float from " +
                      std::to_string(std::bit_cast<float>(sweep.first)),
                  i, "at input", v);
  return bits;
}

std::optional<std::vector<uint8_t>> denseAlphaTable() {
  return currentDrawer ? currentDrawer->denseAlphaTable() : std::nullopt;
}

// Random triangles of all sizes, perspective, overlapping, some crossing the near plane and the
// frustum's sides, some slivers and a coplanar duplicate of the first.
ClipSpaceMesh randomTriangles(unsigned seed, int triangles) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), wRange(0.3f, 3.0f);
  ClipSpaceMesh mesh;
  const auto add = [&](glm::vec4 p, glm::vec2 uv) {
    mesh.vertices.push_back({p, uv});
    mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
  };
  for (int k = 0; k < triangles; ++k) {
    const float scale = k % 3 == 0 ? 0.05f : (k % 3 == 1 ? 0.4f : 1.6f);
    const glm::vec2 centre = drawPoint([&] { return unit(random); });
    for (int corner = 0; corner < 3; ++corner) {
      const float w = k % 7 == 0 && corner == 0 ? -0.5f : wRange(random);
      const glm::vec2 xy = centre + scale * drawPoint([&] { return unit(random); });
      const float z = 0.8f * unit(random);
      add({xy.x * std::fabs(w), xy.y * std::fabs(w), z * std::fabs(w) - (w < 0 ? 1.0f : 0.0f), w},
          {0.5f + 0.5f * unit(random), 0.5f + 0.5f * unit(random)});
    }
  }
  for (int corner = 0; corner < 3; ++corner)
    add(mesh.vertices[static_cast<size_t>(corner)].position, {0.1f, 0.9f});
  return mesh;
}

namespace {

// The mesh's vertices and indices in buffers, bound to attributes 0 (clip position) and 1 (uv)
// of a vertex array; `names` deletes them.
GLuint meshVertexArray(const ClipSpaceMesh& mesh, Names& names) {
  GLuint array = 0, buffer[2] = {0, 0};
  glCreateVertexArrays(1, &array);
  names.arrays.push_back(array);
  glCreateBuffers(2, buffer);
  names.buffers.assign(buffer, buffer + 2);
  glNamedBufferData(buffer[0], static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(ClipVertex)),
                    mesh.vertices.data(), GL_STATIC_DRAW);
  glNamedBufferData(buffer[1], static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                    mesh.indices.data(), GL_STATIC_DRAW);
  glVertexArrayVertexBuffer(array, 0, buffer[0], 0, sizeof(ClipVertex));
  glVertexArrayElementBuffer(array, buffer[1]);
  glEnableVertexArrayAttrib(array, 0);
  glEnableVertexArrayAttrib(array, 1);
  glVertexArrayAttribFormat(array, 0, 4, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, position));
  glVertexArrayAttribFormat(array, 1, 2, GL_FLOAT, GL_FALSE, offsetof(ClipVertex, uv));
  glVertexArrayAttribBinding(array, 0, 0);
  glVertexArrayAttribBinding(array, 1, 0);
  return array;
}

// The depth texture's values, one per pixel of `out`.
void readDepth(GLuint depth, bool z24, std::vector<float>& out) {
  const size_t pixels = out.size();
  const auto bytes = [&](size_t element) { return static_cast<GLsizei>(pixels * element); };
  if (z24) {
    // The stored integer d in the top 24 bits of a 32-bit unorm, returned as the oracle keeps
    // it: d / (2^24 - 1) in float (reference/visibility.h, PixelHit::depth).
    std::vector<uint32_t> stored(pixels);
    glGetTextureImage(depth, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, bytes(4), stored.data());
    for (size_t i = 0; i < pixels; ++i) out[i] = static_cast<float>(stored[i] >> 8) / 16777215.0f;
  } else {
    glGetTextureImage(depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, bytes(4), out.data());
  }
}

}  // namespace

RasterReadback drawTrianglesHere(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                                 Interpolation interpolation) {
  const std::string qualifier =
      interpolation == Interpolation::kNoPerspective ? "noperspective " : "";
  const std::string vertex = "#version 450 core\n" + qualifier + R"(out vec2 vUV;
layout(location = 0) in vec4 aClipPosition;
layout(location = 1) in vec2 aUV;
flat out float vTriangle;
void main() {
  vUV = aUV;
  vTriangle = float(gl_VertexID / 3 + 1);
  gl_Position = aClipPosition;
}
)";
  // The triangle as a flat float from its vertices (each triangle has its own three, in order),
  // not gl_PrimitiveID, into a float target: an implementation that loses integer clears
  // (softpipe, tests/gl/softpipe_rules_test.cpp) is still measured.
  const std::string fragment = "#version 450 core\n" + qualifier + R"(in vec2 vUV;
flat in float vTriangle;
layout(location = 0) out vec4 outTriangle;
layout(location = 1) out vec4 outUV;
layout(location = 2) out vec4 outDerivatives;
void main() {
  outTriangle = vec4(vTriangle, 0.0, 0.0, 0.0);
  outUV = vec4(vUV, 0.0, 0.0);
  outDerivatives = vec4(dFdxFine(vUV), dFdyFine(vUV));
}
)";
  const GlProgram program(vertex, fragment);
  const int width = viewport.width, height = viewport.height;
  Names names;
  const GLuint triangles = names.texture(GL_RGBA32F, width, height);
  const GLuint uvs = names.texture(GL_RGBA32F, width, height);
  const GLuint derivatives = names.texture(GL_RGBA32F, width, height);
  const bool z24 = format == DepthFormat::kDepth24;
  const GLuint depth =
      names.texture(z24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F, width, height);
  const GLuint framebuffer = names.framebuffer();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, triangles, 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, uvs, 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT2, derivatives, 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
  const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  glNamedFramebufferDrawBuffers(framebuffer, 3, buffers);
  const GLfloat zeros[4] = {0, 0, 0, 0}, one = 1.0f;
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, zeros);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zeros);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 2, zeros);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);

  const GLuint array = meshVertexArray(mesh, names);

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(program.id());
  glBindVertexArray(array);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_DEPTH_TEST);

  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<glm::vec4> triangle(pixels);
  std::vector<glm::vec4> uv(pixels);
  RasterReadback result{{},
                        std::vector<glm::vec2>(pixels),
                        std::vector<glm::vec4>(pixels),
                        std::vector<float>(pixels)};
  const auto bytes = [&](size_t element) { return static_cast<GLsizei>(pixels * element); };
  glGetTextureImage(triangles, 0, GL_RGBA, GL_FLOAT, bytes(16), triangle.data());
  glGetTextureImage(uvs, 0, GL_RGBA, GL_FLOAT, bytes(16), uv.data());
  glGetTextureImage(derivatives, 0, GL_RGBA, GL_FLOAT, bytes(16), result.derivatives.data());
  readDepth(depth, z24, result.depth);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  requireNoError("triangles");
  result.triangle.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    result.triangle[i] = static_cast<int32_t>(triangle[i].x) - 1;
    result.uv[i] = glm::vec2(uv[i]);
  }
  return result;
}

}  // namespace vt::calibrate
