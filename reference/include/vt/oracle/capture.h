#pragma once
// Captures: frames another renderer drew, with everything the oracle needs to draw them again, so
// that `vt crosscheck --captures` (or checkCapture below) can validate any engine in CI. One
// capture is a JSON manifest next to its data files; reference/validate-your-renderer.md specifies
// the format:
//
//   frame0007.json             the manifest: texture and its identity, viewport, renderer, cache
//                              state, needbuffer encoding, filtering, the files below, and
//                              optionally the precision model file that judges the frame
//   frame0007.vertices.f32     clip-space vertices (x, y, z, w, s, t), float32 little-endian
//   frame0007.indices.u32      three per triangle, uint32 little-endian (optional)
//   frame0007.color.png        RGBA8, rows top to bottom
//   frame0007.need.png         8-bit needbuffer: RGBA8, rows top to bottom, or
//   frame0007.need.u32         32-bit needbuffer: four uint32 little-endian per pixel, rows top
//                              to bottom
//
// Files are named relative to the manifest's folder.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "vt/oracle/cache.h"
#include "vt/oracle/compare.h"
#include "vt/oracle/export.h"
#include "vt/oracle/render.h"
#include "vt/oracle/scene.h"
#include "vt/oracle/texture.h"

namespace vt::oracle {

inline constexpr int kCaptureVersion = 1;

struct Capture {
  std::string renderer;           // GL_RENDERER or the engine's name, for reports
  std::filesystem::path texture;  // the .vt file (resolved against the manifest's folder)
  // The precision model file (`vt calibrate`'s output) the frame is to be judged under, resolved
  // against the manifest's folder; empty when the capture names none. `vt crosscheck --captures
  // --model auto` uses it; checkCapture(capture, texture, capture.model) does the same here.
  std::filesystem::path model;
  // The shipped model ("llvmpipe", "softpipe", "exact") whose fingerprint the capturing program
  // reproduced on the renderer bit for bit (`vt fly --capture` runs it); empty when none did or
  // none was run. `--model auto` trusts a shipped pinned model only on this evidence, never on
  // the renderer's name.
  std::string fingerprint;
  uint64_t textureIdentity = 0;  // Texture::identity() of the file the frame was drawn from
  Scene scene;
  CacheState cache;
  NeedEncoding needEncoding = NeedEncoding::k32Bit;
  Filtering filtering = Filtering::kTrilinear;
  Sampling sampling = Sampling::kTexelFetch;
  std::vector<uint8_t> color;  // RGBA8, rows bottom to top (as glReadPixels returns them)
  std::vector<uint32_t> need;  // four per pixel, rows bottom to top
};

// Reads and validates a capture: every field present and of its type, the format version known,
// the encoding, filtering and sampling names known, data files of exactly the sizes the viewport
// and counts ask for, indices within the vertices, values an encoding can hold. Throws Error
// naming the manifest (or data file) and the problem. Does not open the texture.
VT_ORACLE_API Capture readCapture(const std::filesystem::path& manifest);

// Writes `capture` as `manifest` (a .json path) and its data files next to it, each through a
// temporary file renamed into place, the manifest last: a folder never holds a manifest whose
// data is partly written. The texture is named relative to the manifest's folder.
VT_ORACLE_API void writeCapture(const std::filesystem::path& manifest, const Capture& capture);

// The manifests (*.json) of a folder, by name.
VT_ORACLE_API std::vector<std::filesystem::path> findCaptures(const std::filesystem::path& folder);

// The oracle's render options for a capture under `profile`.
VT_ORACLE_API RenderOptions renderOptions(const Capture& capture, Profile profile);

struct CaptureCheck {
  Frame oracle;           // what the oracle drew from the capture's inputs
  Comparison comparison;  // the capture's frame against it
};

// Verifies that `texture` is the capture's (its identity), draws the capture's inputs with the
// oracle and compares them with the captured frame. Throws Error on a texture that is not the
// capture's, or inputs the oracle cannot draw (see render).
// Under a model with free parameters the result sets are built where the captured frame differs
// (SetScope::kDiffering, RenderOptions' judged frame), or for every pixel.
enum class SetScope { kDiffering, kEveryPixel };
VT_ORACLE_API CaptureCheck checkCapture(const Capture& capture, const Texture& texture,
                                        Profile profile, unsigned threads = 0,
                                        SetScope scope = SetScope::kDiffering);
// The same under the precision model of a model file (src/render/precision_model_file.h).
VT_ORACLE_API CaptureCheck checkCapture(const Capture& capture, const Texture& texture,
                                        const std::filesystem::path& modelFile,
                                        unsigned threads = 0,
                                        SetScope scope = SetScope::kDiffering);

}  // namespace vt::oracle
