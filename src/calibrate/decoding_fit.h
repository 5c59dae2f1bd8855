#pragma once
// Block decoding (render/arithmetic.h; the members: format/block_decoding.h): texelFetch of every
// texel of a BC1 and a BC3 probe texture of random blocks, uploaded as the GL renderer uploads its
// cache. The colour rule is fitted on both textures' RGB, the alpha rule on BC3's alpha; each is
// pinned where a member reproduces every texel. The probe blocks are chosen so that every two
// members differ on some texel (tests/format/block_decoding_test.cpp checks it), so a pinned
// member is the only one consistent. A texel outside every member's and the specification's
// range (decodeTexelRange) is non-conformance.

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "calibrate/family_fit.h"
#include "format/block_decoding.h"

namespace vt::calibrate {

struct DecodingFit {
  ParameterFit colour, alpha;
  BlockDecoding decoding;     // the members chosen (pinned or closest)
  uint64_t outsideRange = 0;  // channels beyond decodeTexelRange, or not an 8-bit value
  bool pinned() const { return colour.pinned && alpha.pinned; }
};

// The dense BC3 alpha table a GPU's probe folder may hold (scripts/bc3-alpha-probe.py): for every
// end-point pair (a0 slow, a1 fast) the alphas at indices 2 to 7, one byte each. When no member
// reproduces BC3 alpha, the weights member (format/block_decoding.h) is fitted: per step the
// integer weights every measured texel allows, from the table where the folder has one, else
// from the 64 x 64 probe; pinned where each step allows exactly one.
inline constexpr const char* kDenseAlphaTableName = "bc3-alpha.u8";
inline constexpr size_t kDenseAlphaTableBytes = 65536 * 6;

// The probe texture of `format` (bc1 or bc3): kDecodingProbeSide x kDecodingProbeSide texels.
inline constexpr int kDecodingProbeSide = 64;
std::vector<std::byte> decodingProbeBlocks(PixelFormat format);

// What each texel of the probe of `format` decodes to under `decoding`, row by row.
std::vector<BlockTexel> decodeProbe(PixelFormat format, BlockDecoding decoding);

// texelFetch of every texel of the probe of `format` on the implementation, row by row.
std::vector<glm::vec4> drawDecodingProbe(PixelFormat format);

// Whether `decoding` reproduces the drawn probes (bc1 and bc3) bit for bit.
bool reproducesDecoding(const std::vector<glm::vec4>& bc1, const std::vector<glm::vec4>& bc3,
                        BlockDecoding decoding);

DecodingFit fitBlockDecoding();

}  // namespace vt::calibrate
