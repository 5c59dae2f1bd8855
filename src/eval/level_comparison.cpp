#include "eval/level_comparison.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "eval/evaluation.h"
#include "eval/image_metrics.h"
#include "render/cache_state.h"

namespace vt {
namespace {

// A stored page's P x P interior as RGBA8 rows.
std::vector<uint8_t> interior(const VirtualTextureReader& reader, PageId page) {
  const TextureDescription& d = reader.description();
  const std::vector<std::byte> texels = reader.readPage(page);
  const uint32_t side = d.storedPageSide(), p = d.pageSize;
  std::vector<uint8_t> rgba(size_t{p} * p * 4);
  for (uint32_t y = 0; y < p; ++y)
    for (uint32_t x = 0; x < p; ++x) {
      const glm::u8vec4 v = expandToRgba(
          texels.data() + (size_t{y + d.border} * side + x + d.border) * d.channels, d.channels);
      for (int c = 0; c < 4; ++c) rgba[(size_t{y} * p + x) * 4 + size_t(c)] = v[c];
    }
  return rgba;
}

}  // namespace

std::vector<LevelComparison> compareLevels(const VirtualTextureReader& a,
                                           const VirtualTextureReader& b) {
  requireSamePages(a, b);
  const TextureDescription& d = a.description();
  const int p = static_cast<int>(d.pageSize);
  std::vector<LevelComparison> levels(d.levelCount);
  std::vector<double> squares(d.levelCount, 0.0);
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    levels[m].level = m;
    levels[m].meanSsim = 0.0;  // a sum until the pages are counted
  }
  for (uint64_t slot = 0; slot < a.storedPageCount(); ++slot) {
    const PageId page = fromAbsoluteIndex(a.storedPage(slot));
    if (!b.contains(page)) continue;
    const std::vector<uint8_t> x = interior(a, page), y = interior(b, page);
    LevelComparison& level = levels[page.level];
    level.meanSsim += ssim({p, p, x}, {p, p, y});
    for (size_t i = 0; i < x.size(); ++i)
      if (i % 4 != 3) {
        const double e = double(x[i]) - double(y[i]);
        squares[page.level] += e * e;
      }
    ++level.pages;
  }
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    LevelComparison& level = levels[m];
    if (level.pages == 0) {
      level.meanSsim = 1.0;  // nothing differs
      continue;
    }
    level.meanSsim /= static_cast<double>(level.pages);
    const double mse = squares[m] / (static_cast<double>(level.pages) * p * p * 3);
    level.rmse = std::sqrt(mse);
    level.psnrDb = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse)
                           : std::numeric_limits<double>::infinity();
  }
  return levels;
}

nlohmann::json levelComparisonJson(const VirtualTextureReader& b,
                                   const std::vector<LevelComparison>& levels) {
  nlohmann::json rows = nlohmann::json::array();
  for (const LevelComparison& l : levels)
    rows.push_back({{"level", l.level},
                    {"pages", l.pages},
                    {"mean_ssim", l.meanSsim},
                    {"rmse", l.rmse},
                    {"psnr_db", std::isfinite(l.psnrDb) ? nlohmann::json(l.psnrDb) : nullptr}});
  return {{"texture", b.path().string()}, {"levels", rows}};
}

}  // namespace vt
