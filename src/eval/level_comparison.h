#pragma once
// Two virtual textures of the same pages compared level by level (`vt info A --against B`): the
// error one format's encoding adds to the other, apart from any streaming. Each page stored in
// both is read (decoded under the exact point's block decoding) and its P x P interior compared:
// SSIM as the evaluations measure it (eval/image_metrics.h, 8 x 8 uniform windows on luminance)
// averaged over the level's pages, and the RMSE and PSNR of R, G and B over all their texels.

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "format/virtual_texture_reader.h"

namespace vt {

struct LevelComparison {
  uint32_t level = 0;
  uint64_t pages = 0;  // stored in both
  double meanSsim = 1.0, rmse = 0.0, psnrDb = 0.0;  // psnrDb infinite for identical levels
};

// Throws InputError naming `b` when its pages are not `a`'s (page size, border, levels).
std::vector<LevelComparison> compareLevels(const VirtualTextureReader& a,
                                           const VirtualTextureReader& b);

// {"texture": b's path, "levels": [{"level", "pages", "mean_ssim", "rmse", "psnr_db"}, ...]}
// (psnr_db null for identical levels).
nlohmann::json levelComparisonJson(const VirtualTextureReader& b,
                                   const std::vector<LevelComparison>& levels);

}  // namespace vt
