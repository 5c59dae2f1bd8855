// Types of the virtual-texture shader logic (docs/design.md section 3), in the common subset of
// GLSL 4.50 and C++20 with GLM: this file is compiled by the GL driver and, verbatim, by the C++
// compiler (shader/shader_cpp.h includes it at namespace scope).
//
// Values that differ from fragment to fragment have their own type names, so that the C++ build
// can give them one value per fragment or one SIMD lane per fragment (shader/shader_cpp.h,
// shader/shader_lanes.h); in GLSL they are GLSL's own scalar types. Uniform values keep the plain
// names.
#ifndef VT_CPP
#define vfloat float
#define vint int
#define vuint uint
#define vbool bool
#endif

// What the fragment logic knows of the texture and the page cache (uniforms in GL).
struct VtParameters {
  int pageSize;     // P, texels per page side
  int border;       // B, texels of border around every stored page (>= 1)
  int finestLevel;  // L: levels 0 (coarsest, one page) .. L (finest)
  int trilinear;    // 1: blend two levels by the fractional lod; 0: bilinear at the needed level
  int exactFilter;  // 1: bilinear from four texel fetches in float; 0: the sampler's GL_LINEAR
  int need8;        // 1: 8-bit needbuffer encoding (thesis 3.2.3.2); 0: 32-bit
  int needScaleLog2;  // k: the frame is drawn at 1/2^k of the screen's resolution per axis (a
                      // reduced needbuffer); the LOD divides its derivatives by 2^k, exactly
  vec2 cacheSize;   // the page cache texture, in texels
};
