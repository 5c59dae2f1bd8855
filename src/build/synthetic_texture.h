#pragma once
// A generated virtual texture for tests, benchmarks and the demo: every level shows its own hue,
// a checkerboard whose squares are P/8 texels of that level (so every level adds detail and has
// NoiseValues above zero), a gradient along s and t, and a one-texel line on the page edges.
// Borders come from the neighbouring texels, clamped at the texture's edge, as `vt build` cuts
// them. The same description gives the same bytes.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "format/texture_description.h"

namespace vt {

struct SyntheticTexture {
  TextureDescription description;
  // Sparse when set: only the pages that intersect the disc of this radius around the texture's
  // centre (in texture coordinates, [0, 1]^2) are stored.
  std::optional<double> discRadius;
  // Store the ancestor errors (build/ancestor_error.h) too: a version-3 file.
  bool ancestorErrors = false;
};

// The stored texels of one page, borders included.
std::vector<std::byte> syntheticPage(const TextureDescription& description, PageId page);

// The absolute indices of the pages a synthetic texture stores, rising.
std::vector<uint64_t> syntheticStoredPages(const SyntheticTexture& texture);

// Writes the texture (pages and NoiseValues) to `path` through VirtualTextureWriter.
void writeSyntheticTexture(const std::filesystem::path& path, const SyntheticTexture& texture);

}  // namespace vt
