#include "scene/missing_texture.h"

#include <array>
#include <vector>

#include "common/image_file.h"

namespace vt {

std::filesystem::path writeMissingTexture(const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / "missing_texture.png";
  if (std::filesystem::exists(path)) return path;
  constexpr uint32_t kSquare = 8;
  constexpr std::array<std::byte, 3> kMagenta = {std::byte{255}, std::byte{0}, std::byte{255}};
  constexpr std::array<std::byte, 3> kBlack = {std::byte{0}, std::byte{0}, std::byte{0}};
  std::vector<std::byte> texels;
  texels.reserve(kMissingTextureSide * kMissingTextureSide * 3);
  for (uint32_t y = 0; y < kMissingTextureSide; ++y)
    for (uint32_t x = 0; x < kMissingTextureSide; ++x) {
      const auto& colour = ((x / kSquare + y / kSquare) % 2 == 0) ? kMagenta : kBlack;
      texels.insert(texels.end(), colour.begin(), colour.end());
    }
  std::filesystem::create_directories(folder);
  writeImage8(path, kMissingTextureSide, kMissingTextureSide, 3, texels);
  return path;
}

void useMissingTexture(SourceTexture& texture, const std::filesystem::path& folder) {
  texture.missing = true;
  texture.file = writeMissingTexture(folder);
  texture.width = texture.height = kMissingTextureSide;
}

}  // namespace vt
