#pragma once
// Ancestor errors (`vt build --ancestor-errors`; beyond the thesis, docs/streaming.md): for each
// stored page q and each coarser level l, how much worse q looks when the renderer shows q's
// ancestor on level l in its place, measured as the evaluations measure a frame. The NoiseValue
// (build/noise_value.h) is one step of this, as a luminance RMSE; summed up the levels it is only
// an estimate of the error through a distant ancestor, which these are measured on.
//
//   E_q(l) = 1 - mean SSIM (common/structural_similarity.h: 8 x 8 uniform windows, every window
//            inside the page, Rec. 709 luminance in [0, 255] of the stored components)
//            between q's P x P interior and the ancestor's texels resampled bilinearly at q's
//            texel centres.
//
// Texel i of q (its centre at i + 0.5, q at (x, y) on level L) lies at ((x mod 2^d) P + i + 0.5)
// / 2^d texels into the interior of its ancestor on level l = L - d; the ancestor's border supplies
// the neighbours bilinear filtering reads at the edge (indices clamped to the stored page when
// B = 0), as the NoiseValue reads its parent's. E_q(l) lies in [0, 2]; pages with P < 8 are one
// window.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "format/page_address.h"
#include "format/texture_description.h"
#include "format/virtual_texture_writer.h"

namespace vt {

inline constexpr uint32_t kAncestorErrorWindow = 8;  // the evaluations' SSIM window (appendix A.2)

// Luminance in [0, 255] of each texel of a stored page ((P + 2B)^2, borders included), from its
// RGBA8 or 1 to 3 channel texels: Rec. 709 Y of R, G, B; the first component with 1 or 2.
std::vector<float> pageLuminance(const TextureDescription& description,
                                 std::span<const std::byte> texels);

// E_q(l) of `page` shown through its ancestor on `ancestorLevel` (< page.level), from both pages'
// luminance (pageLuminance).
float ancestorError(const TextureDescription& description, PageId page,
                    std::span<const float> pageLuminance, uint32_t ancestorLevel,
                    std::span<const float> ancestorLuminance);

// The table of every stored page: `storedPages` (absolute indices, rising, holding the ancestors
// of every page they hold), each row levelCount - 1 entries, entry l = E_q(l) for l < q's level
// and 0 beyond. `texelsOf` returns a stored page's texels (decoded to RGBA8 for the block
// formats); it is called from TBB's workers. The same values for any thread count.
std::vector<float> ancestorErrorTable(
    const TextureDescription& description, std::span<const uint64_t> storedPages,
    const std::function<std::vector<std::byte>(PageId)>& texelsOf);

// The table of the pages `writer` has written, read back from its file and decoded for the block
// formats (what the renderers show); every stored page must have been written.
std::vector<float> ancestorErrorsOfWrittenPages(const VirtualTextureWriter& writer);

}  // namespace vt
