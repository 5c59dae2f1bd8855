#pragma once
// Renders a scene exactly as the virtual-texture shader of thesis 3.2.3 does on a GPU: per pixel
// the Heckbert LOD from fine derivatives of 2x2 pixel quads (helper pixels included), the
// needbuffer entry of the page it needs, the indirection lookup and bordered bilinear or manual
// trilinear filtering from the cache state. The result is the same bytes for any thread count.
//
// Images are rows bottom to top (window y up, as glReadPixels returns them): pixel (px, py) is
// element py * width + px.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "vt/oracle/cache.h"
#include "vt/oracle/export.h"
#include "vt/oracle/scene.h"
#include "vt/oracle/texture.h"

namespace vt::oracle {

// The precision model the oracle judges under (docs/design.md section 3, "Exactness"): within which
// limits the other implementation may compute differently from the oracle.
//   exact     IEEE float in source order, every parameter pinned: golden images, bit for bit
//   llvmpipe  Mesa's llvmpipe on x86-64 with FMA, every parameter pinned: bit for bit
//   gl45      only what the OpenGL 4.5 and GLSL 4.50 specifications guarantee (dEQP's minimum
//             precisions where they are silent): every pixel gets the set of all values a
//             conforming implementation could produce, and compare() accepts exactly those
//   softpipe  Mesa's softpipe, every parameter pinned: bit for bit
enum class Profile { kExact, kLlvmpipe, kGl45, kSoftpipe };

VT_ORACLE_API Profile parseProfile(const std::string& name);  // "exact", ...; throws Error
VT_ORACLE_API std::string toString(Profile profile);
// The model for a GL_RENDERER string: llvmpipe for Mesa's llvmpipe on a CPU with FMA, softpipe
// for Mesa's softpipe, gl45 otherwise.
VT_ORACLE_API Profile profileForRenderer(const std::string& glRenderer);

// The needbuffer encodings (thesis 3.2.3.2), per pixel (r, g, b, a):
//   k32Bit (RGBA32UI)  (px, py, m, 1); no geometry (0, 0, 0, 0)
//   k8Bit  (RGBA8UI)   (px mod 256, py mod 256, m, px / 256 + 16 * (py / 256)); no geometry
//                      (0, 0, 255, 0); textures of up to 4096 pages per side (L <= 12)
enum class NeedEncoding { k32Bit, k8Bit };
// Trilinear: two bilinear lookups on the levels around the LOD, blended in the shader.
enum class Filtering { kTrilinear, kBilinear };
// How a bilinear lookup reads the cache texture: four texelFetch calls weighted in float (the
// exact mode), or the sampler's GL_LINEAR.
enum class Sampling { kTexelFetch, kHardwareLinear };

VT_ORACLE_API std::string toString(NeedEncoding encoding);  // "need32", "need8"
VT_ORACLE_API std::string toString(Filtering filtering);    // "trilinear", "bilinear"
VT_ORACLE_API std::string toString(Sampling sampling);      // "texel_fetch", "hardware_linear"

struct RenderOptions {
  Profile profile = Profile::kExact;
  // A precision model file (src/render/precision_model_file.h) to judge under instead of
  // `profile`; empty: `profile`. Throws Error when it cannot be read.
  std::string modelFile;
  NeedEncoding needEncoding = NeedEncoding::k32Bit;
  Filtering filtering = Filtering::kTrilinear;
  Sampling sampling = Sampling::kTexelFetch;
  unsigned threads = 0;  // 0: every core
  // The frame to be judged, when it is known before the oracle draws (a capture, or a frame drawn
  // first): under a model with free parameters, result sets are then built only where its colour
  // or needbuffer differs from the oracle's own value, the pixels compare() does not find
  // identical; the others need none, and a conforming implementation differs at a few percent of
  // its pixels. compare() must be given this same frame (it throws Error at a differing pixel
  // without a set), and `ambiguous` and the set widths count the differing pixels alone. Rows and
  // encoding as the oracle's Frame; read during render() only. Empty: every pixel's set.
  std::span<const uint8_t> judgedColor;
  std::span<const uint32_t> judgedNeed;
};

// Every pixel's result set under a model with free parameters (opaque; compare() reads it).
struct ResultSets;

struct Frame {
  Viewport viewport;
  std::vector<uint8_t> color;  // RGBA8; (0, 0, 0, 0) where no geometry
  std::vector<uint32_t> need;  // four per pixel, in the chosen encoding
  std::vector<float> depth;    // window depth; 1 where no geometry
  // 1 where the pixel's result set holds more than one value (always 0 under exact, llvmpipe).
  std::vector<uint8_t> ambiguous;
  NeedEncoding needEncoding = NeedEncoding::k32Bit;
  std::string model;                       // the model's name
  std::shared_ptr<const ResultSets> sets;  // none under a pinned model
  bool judged = false;  // sets built only where RenderOptions' judged frame differs
};

// A cache state with its pages read from the texture and its indirection table derived, for
// rendering many frames from one state (reading the pages is most of a small frame's time).
// Throws Error when a page is not stored in the texture, frames overlap or lie outside the grid,
// or the root is not resident. Keeps a reference to `texture`, which must outlive it.
class VT_ORACLE_API PreparedCache {
 public:
  PreparedCache(const Texture& texture, const CacheState& state);
  PreparedCache(PreparedCache&&) noexcept;
  PreparedCache& operator=(PreparedCache&&) noexcept;
  ~PreparedCache();

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// Throws Error as PreparedCache does, or when the 8-bit encoding cannot name the texture's pages
// (more than 12 levels below the root) or the viewport is not 1..16384 pixels per side.
VT_ORACLE_API Frame render(const Texture& texture, const Scene& scene, const CacheState& cache,
                           const RenderOptions& options);
VT_ORACLE_API Frame render(const Texture& texture, const Scene& scene, const PreparedCache& cache,
                           const RenderOptions& options);

}  // namespace vt::oracle
