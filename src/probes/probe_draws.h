#pragma once
// The draws `vt calibrate` measures an OpenGL implementation with, on the current context: each
// feeds chosen inputs through one GL feature and reads the results back exactly (32-bit float
// and integer targets), so that calibration.h can compare them with the oracle's arithmetic.
// They live below both of their users: the calibration (src/calibrate/) and vt-capture, the
// GPU-side program that draws them and writes their results as files (capture/probe_files.h);
// they keep the calibration's namespace.

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "format/texture_description.h"
#include "probes/function_sweeps.h"
#include "render/render_settings.h"
#include "scene/clip_space_mesh.h"

namespace vt::calibrate {

// A full-screen draw of `width` x (inputs / width) pixels. The fragment shader reads its pixel's
// input as `vec4 x` (an RGBA32F texelFetch), may read `uTexture` (an RGBA8 sampler of `texels`,
// `textureSize`, clamp to edge, GL_LINEAR or GL_NEAREST, no mipmaps) and assigns `precise vec4
// result` in `body`; the results come back as floats, row by row.
struct ShaderProbe {
  std::string body;
  std::vector<glm::vec4> inputs;
  int width = 256;
  std::vector<glm::u8vec4> texels;  // empty: no texture bound
  glm::ivec2 textureSize{0, 0};
  // Instead of `texels`: a texture of a block format (bc1 as GL_COMPRESSED_RGB_S3TC_DXT1_EXT,
  // bc3 as GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, as the GL renderer's cache), `textureSize` texels
  // (multiples of 4) of these blocks, rows of increasing t.
  PixelFormat blockFormat = PixelFormat::kUnorm8;
  std::vector<std::byte> blocks;
  bool linear = false;
  // The viewport covered by one triangle larger than it (the clipper cuts it), or by two that
  // fit it exactly (nothing is clipped): implementations may shade the two kinds of batch with
  // different arithmetic (softpipe's denormal mode: reference/softpipe-arithmetic.md, 5.3).
  bool clipped = true;
};
std::vector<glm::vec4> runShaderProbe(const ShaderProbe& probe);

// The same draw into an RGBA8 target: `result` is converted by the implementation's colour
// conversion (GL 4.5 section 2.3.5.2), read back as bytes.
std::vector<glm::u8vec4> runColourProbe(const ShaderProbe& probe);

// What a draw of `mesh` leaves per pixel (bottom row first): the triangle that passed GL_LESS
// against a depth buffer (32F or Z24) cleared to 1 (-1 for none; each triangle must have its own
// three vertices, in order, as randomTriangles in calibration.cpp makes them), its texture
// coordinates, their fine derivatives (ds/dx, dt/dx, ds/dy, dt/dy) and the depth stored. The
// coordinates are interpolated perspective-correct (GLSL's default), or `noperspective`: linearly
// in window space.
enum class Interpolation { kPerspective, kNoPerspective };
struct RasterReadback {
  std::vector<int32_t> triangle;
  std::vector<glm::vec2> uv;
  std::vector<glm::vec4> derivatives;
  std::vector<float> depth;
};
// `triangles` random triangles (a fixed `seed`) of all sizes, perspective, overlapping, some
// crossing the near plane and the frustum's sides, some slivers, and last a coplanar duplicate of
// the first: each with its own three vertices.
ClipSpaceMesh randomTriangles(unsigned seed, int triangles);

RasterReadback drawTriangles(const ClipSpaceMesh& mesh, Viewport viewport,
                             DepthFormat format = DepthFormat::kDepth32F,
                             Interpolation interpolation = Interpolation::kPerspective);

// The implementation's names (GL_RENDERER, GL_VERSION, GL_VENDOR).
struct ProbeIdentity {
  std::string renderer, version, vendor;
};
ProbeIdentity probeIdentity();

// Where runShaderProbe, runColourProbe, drawTriangles and probeIdentity go: to the current
// context (no drawer set), or to a drawer that records them or replays draws recorded elsewhere
// (calibrate/recorded_probes.h). One drawer at a time, set by UsingProbeDrawer on the calling
// thread.
class ProbeDrawer {
 public:
  virtual ~ProbeDrawer() = default;
  virtual std::vector<glm::vec4> shader(const ShaderProbe& probe) = 0;
  virtual std::vector<glm::u8vec4> colour(const ShaderProbe& probe) = 0;
  virtual RasterReadback triangles(const ClipSpaceMesh& mesh, Viewport viewport,
                                   DepthFormat format, Interpolation interpolation) = 0;
  virtual ProbeIdentity identity() = 0;
  // A dense BC3 alpha table measured beside the probes (decoding_fit.h), if the drawer has one.
  virtual std::optional<std::vector<uint8_t>> denseAlphaTable() { return std::nullopt; }
  // A function sweep drawn beside the probes (probes/function_sweeps.h), if the drawer has it.
  virtual std::optional<std::vector<uint32_t>> sweep(const FunctionSweep&) { return std::nullopt; }
  // Whether the next `draws` draws, a group added to the pack after folders were drawn without
  // it, are there: always, but for a drawer replaying a folder that ends where the group begins.
  virtual bool holdsGroup(size_t /*draws*/) { return true; }
};

// Whether the set drawer holds an optional group of `draws` draws that come next (true without
// a drawer: this context draws them). A group comes after every draw that is not optional, so a
// folder drawn before the group existed replays as it did.
bool holdsOptionalGroup(size_t draws);

// The set drawer's dense BC3 alpha table; none without a drawer (this context draws no such
// probe: scripts/bc3-alpha-probe.py makes it for a GPU).
std::optional<std::vector<uint8_t>> denseAlphaTable();

class UsingProbeDrawer {
 public:
  explicit UsingProbeDrawer(ProbeDrawer& drawer);
  ~UsingProbeDrawer();
  UsingProbeDrawer(const UsingProbeDrawer&) = delete;
  UsingProbeDrawer& operator=(const UsingProbeDrawer&) = delete;

 private:
  ProbeDrawer* previous_;
};

// The draws on the current context, whatever drawer is set.
std::vector<glm::vec4> drawShaderProbeHere(const ShaderProbe& probe);
std::vector<glm::u8vec4> drawColourProbeHere(const ShaderProbe& probe);
RasterReadback drawTrianglesHere(const ClipSpaceMesh& mesh, Viewport viewport, DepthFormat format,
                                 Interpolation interpolation = Interpolation::kPerspective);
ProbeIdentity identityHere();

}  // namespace vt::calibrate
