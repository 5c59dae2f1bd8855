// The per-fragment logic of virtual texturing (thesis 3.2.3 and appendix B, docs/design.md section
// 3), written once in the common subset of GLSL 4.50 and C++20 with GLM. The GL renderer compiles
// it in its fragment shader; the CPU oracle includes it verbatim inside a class
// (shader/shader_cpp.h).
//
// The backend around it provides:
//   uvec4 vtFetchIndirection(ivec2 page, int level)  entry (fx, fy, i, 0) of page (px, py, m):
//                                                     its frame, or its best resident ancestor's,
//                                                     and that page's level i <= m
//   vec4  vtFetchCacheTexel(ivec2 texel)             one cache texel (texelFetch)
//   vec4  vtSampleCacheLinear(vec2 texel)            the sampler's bilinear filter at a texel
//                                                     position (GL_LINEAR, centres at +0.5)
//   float log2(float)                                 the target's log2 (a precision profile)
//   float sqrt(float)                                 the target's sqrt (IEEE, or measured)
//
// Decisions this file fixes for both backends:
//   - lod = L - clamp(log2(e_max * P * 2^L), 0, L), larger is finer (appendix B). NaN gives the
//     coarsest level 0, a zero derivative (log2 = -Inf) the finest level L.
//   - The needbuffer requests ceil(lod): the finer of the two levels trilinear filtering blends.
//     Trilinear blends floor(lod) and floor(lod) + 1 (at most L) by lod - floor(lod); bilinear
//     samples the requested level.
//   - (s, t) outside [0, 1] is clamped (the texture does not wrap) and NaN becomes 0, so every
//     page index lies inside its level; s = 1.0 belongs to the last page, at its right edge.
//   - Every expression that must not be reassociated or fused is `precise`; clamps are written
//     as comparisons so that NaN has one defined result.
//
// Rules for editing, so that both compilers agree: no `in`/`out` parameters (return structs), no
// swizzles beyond .x .y .z .w, no arithmetic with floating literals (C++ would compute in double;
// comparisons and selections with them are fine), no mix/clamp/min/max on values that may be NaN.
// A value that may differ between fragments is a vfloat, vint, vuint or vbool (types file); a
// choice between such values is vtSelect (a select, never arithmetic), never `?:`, which C++
// cannot apply lane by lane; `?:` and `if` stay for uniform conditions.

// The result for one fragment.
struct VtFragment {
  vec4 color;          // filtered texel colour in [0, 1]
  uvec4 need;          // needbuffer value of the needed page
  vfloat lod;          // fractional level, 0 coarsest .. L finest
  vint neededLevel;    // the level the needbuffer requests
  vint residentLevel;  // the level actually sampled for the needed level (itself or an ancestor)
};

// One level's filtered colour and the level of the page it came from.
struct VtSample {
  vec4 color;
  vint residentLevel;
};

// c ? a : b, fragment by fragment: GLSL 4.50's mix with a boolean selects and computes nothing, so
// NaN and infinities pass through unchanged.
vfloat vtSelect(vbool c, vfloat a, vfloat b) { return mix(b, a, c); }
vint vtSelect(vbool c, vint a, vint b) { return mix(b, a, c); }

// x clamped to [0, hi], NaN to 0.
vfloat vtClampOrZero(vfloat x, vfloat hi) {
  precise vfloat below = vtSelect(x <= hi, x, hi);
  return vtSelect(x >= 0.0, below, 0.0);
}

// Heckbert's edge-compression LOD (appendix B): e_max = sqrt(max(|dUV/dx|^2, |dUV/dy|^2)),
// d = log2(e_max * P * 2^L) clamped to [0, L], lod = L - d. A reduced needbuffer (1/2^k of the
// resolution) sees derivatives 2^k times larger: P * 2^L is scaled by 2^-k with ldexp, exactly,
// so k = 0 gives the same bits as the plain formula.
vfloat vtLevelOfDetail(vec2 dUVdx, vec2 dUVdy, VtParameters p) {
  precise vfloat ex = dUVdx.x * dUVdx.x + dUVdx.y * dUVdx.y;
  precise vfloat ey = dUVdy.x * dUVdy.x + dUVdy.y * dUVdy.y;
  // max(ex, ey), but NaN when either is NaN (both comparisons fail, and ex + ey is NaN).
  precise vfloat larger = vtSelect(ex >= ey, ex, vtSelect(ey >= ex, ey, ex + ey));
  precise vfloat eMax = sqrt(larger);
  precise float finestSide = ldexp(float(p.pageSize) * float(1 << p.finestLevel), -p.needScaleLog2);
  precise vfloat d = log2(eMax * finestSide);
  float L = float(p.finestLevel);
  // NaN (from NaN derivatives) compares false both times and ends at L: the coarsest level.
  precise vfloat upper = vtSelect(d <= L, d, L);
  precise vfloat clamped = vtSelect(upper >= 0.0, upper, 0.0);
  return L - clamped;
}

// The level the needbuffer requests: ceil(lod), in [0, L].
vint vtNeededLevel(vfloat lod) { return vint(ceil(lod)); }

// Page (px, py) of level m under (s, t) in [0, 1]: floor(s * 2^m) (thesis 3.2.3.1), clamped so
// that s = 1.0 falls in the last page.
ivec2 vtPageAt(vec2 uv, vint level) {
  vfloat last = vfloat((1 << level) - 1);
  precise vec2 scaled = uv * vfloat(1 << level);
  return ivec2(vint(vtClampOrZero(floor(scaled.x), last)),
               vint(vtClampOrZero(floor(scaled.y), last)));
}

// 32-bit needbuffer (thesis 3.2.3.2): r = px, g = py, b = m, a = 1 (a = 0: no geometry).
uvec4 vtEncodeNeed32(ivec2 page, vint level) {
  return uvec4(vuint(page.x), vuint(page.y), vuint(level), 1u);
}

// 8-bit needbuffer (thesis 3.2.3.2): r = px mod 256, g = py mod 256, b = m,
// a = px / 256 + (py / 256) * 16, for up to 4096 pages per side. b = 255 marks no geometry.
uvec4 vtEncodeNeed8(ivec2 page, vint level) {
  return uvec4(vuint(page.x & 255), vuint(page.y & 255), vuint(level),
               vuint((page.x >> 8) + (page.y >> 8) * 16));
}

// Where (s, t) lies in the cache, in texels, for the page of level m that the indirection entry
// serves (thesis 3.2.3.3): the frame's origin, the border, and the internal offset
// s * 2^i - px_i (fract(s * 2^i) except at s = 1.0, where it is 1) scaled by P.
vec2 vtCacheTexel(vec2 uv, ivec2 page, vint level, uvec4 entry, VtParameters p) {
  vint i = vint(entry.z);
  ivec2 resident = ivec2(page.x >> (level - i), page.y >> (level - i));
  precise vec2 scaled = uv * vfloat(1 << i);
  precise vec2 inside = scaled - vec2(resident);
  int stored = p.pageSize + 2 * p.border;
  precise vec2 origin =
      vec2(ivec2(vint(entry.x) * stored + p.border, vint(entry.y) * stored + p.border));
  precise vec2 texel = origin + inside * float(p.pageSize);
  return texel;
}

// Bilinear filtering from four texel fetches, in float (the exact mode): texel centres at +0.5.
vec4 vtBilinearExact(vec2 texel) {
  precise vec2 t = texel - vec2(0.5, 0.5);
  vec2 base = floor(t);
  precise vec2 f = t - base;
  ivec2 i0 = ivec2(base);
  vec4 c00 = vtFetchCacheTexel(i0);
  vec4 c10 = vtFetchCacheTexel(i0 + ivec2(1, 0));
  vec4 c01 = vtFetchCacheTexel(i0 + ivec2(0, 1));
  vec4 c11 = vtFetchCacheTexel(i0 + ivec2(1, 1));
  precise vec4 row0 = c00 + (c10 - c00) * f.x;
  precise vec4 row1 = c01 + (c11 - c01) * f.x;
  precise vec4 color = row0 + (row1 - row0) * f.y;
  return color;
}

// The filtered colour of level m at (s, t), from the page or the resident ancestor the
// indirection table names, and that page's level.
VtSample vtSampleLevel(vec2 uv, vint level, VtParameters p) {
  ivec2 page = vtPageAt(uv, level);
  uvec4 entry = vtFetchIndirection(page, level);
  vec2 texel = vtCacheTexel(uv, page, level, entry, p);
  VtSample result;
  result.color = (p.exactFilter != 0) ? vtBilinearExact(texel) : vtSampleCacheLinear(texel);
  result.residentLevel = vint(entry.z);
  return result;
}

// The first half of vtShadeFragment, all a needbuffer pass computes: the LOD from the
// derivatives, the needed level and its needbuffer entry (thesis 3.2.3.1-3.2.3.2). The colour is
// left transparent black and the resident level -1.
VtFragment vtNeedOfFragment(vec2 uvIn, vec2 dUVdx, vec2 dUVdy, VtParameters p) {
  VtFragment result;
  vec2 uv = vec2(vtClampOrZero(uvIn.x, 1.0), vtClampOrZero(uvIn.y, 1.0));
  result.lod = vtLevelOfDetail(dUVdx, dUVdy, p);
  result.neededLevel = vtNeededLevel(result.lod);
  ivec2 page = vtPageAt(uv, result.neededLevel);
  result.need = (p.need8 != 0) ? vtEncodeNeed8(page, result.neededLevel)
                               : vtEncodeNeed32(page, result.neededLevel);
  result.color = vec4(0.0);
  result.residentLevel = vint(-1);
  return result;
}

// Everything the unified shader computes for one fragment (thesis 3.2.3): the LOD from the
// derivatives, the needed page, and the colour from the available set.
VtFragment vtShadeFragment(vec2 uvIn, vec2 dUVdx, vec2 dUVdy, VtParameters p) {
  VtFragment result = vtNeedOfFragment(uvIn, dUVdx, dUVdy, p);
  vec2 uv = vec2(vtClampOrZero(uvIn.x, 1.0), vtClampOrZero(uvIn.y, 1.0));
  if (p.trilinear != 0) {
    vint coarse = vint(floor(result.lod));
    vint fine = vtSelect(coarse < p.finestLevel, coarse + 1, coarse);
    precise vfloat weight = result.lod - vfloat(coarse);
    VtSample c0 = vtSampleLevel(uv, coarse, p);
    VtSample c1 = vtSampleLevel(uv, fine, p);
    precise vec4 color = c0.color + (c1.color - c0.color) * weight;
    result.color = color;
    result.residentLevel = c1.residentLevel;
  } else {
    VtSample only = vtSampleLevel(uv, result.neededLevel, p);
    result.color = only.color;
    result.residentLevel = only.residentLevel;
  }
  return result;
}
