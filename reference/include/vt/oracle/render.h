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
#include <string>
#include <vector>

#include "vt/oracle/cache.h"
#include "vt/oracle/export.h"
#include "vt/oracle/scene.h"
#include "vt/oracle/texture.h"

namespace vt::oracle {

// What a GL implementation computes, so the oracle matches it bit for bit or states a bound:
//   exact     IEEE float in source order, no fused multiply-add, denormals kept; colour within
//             4 units of 8 bits (the Khronos bound for 8-bit linear filtering)
//   llvmpipe  Mesa's llvmpipe on x86-64 with FMA, bit for bit (colour bound 0)
//   nvidia    NVIDIA GPUs: exact arithmetic, 8-bit filter weights, log2 within 2^-22; colour
//             within 4; pixels whose result could change within these bounds are flagged
enum class Profile { kExact, kLlvmpipe, kNvidia };

VT_ORACLE_API Profile parseProfile(const std::string& name);  // "exact", ...; throws Error
VT_ORACLE_API std::string toString(Profile profile);
// The profile for a GL_RENDERER string: llvmpipe for Mesa's llvmpipe, nvidia otherwise.
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
  NeedEncoding needEncoding = NeedEncoding::k32Bit;
  Filtering filtering = Filtering::kTrilinear;
  Sampling sampling = Sampling::kTexelFetch;
  unsigned threads = 0;  // 0: every core
};

// Why a pixel's result could differ on the target within its profile's precision.
enum Ambiguity : uint8_t {
  kNearEdge = 1 << 0,        // pixel centre within 1/256 pixel of the shown triangle's edge
  kNearlyCoplanar = 1 << 1,  // another covering triangle's depth within the depth tolerance
  kPageBoundary = 1 << 2,    // s * 2^m or t * 2^m within 4 ulps of an integer
  kLevelBoundary = 1 << 3,   // LOD within 2^-12 of an integer
  kNearZeroW = 1 << 4,       // |w| below 1e-6 at a pixel of the quad
};

struct Frame {
  Viewport viewport;
  std::vector<uint8_t> color;      // RGBA8; (0, 0, 0, 0) where no geometry
  std::vector<uint32_t> need;      // four per pixel, in the chosen encoding
  std::vector<float> depth;        // window depth; 1 where no geometry
  std::vector<uint8_t> ambiguity;  // Ambiguity bits
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
