#include "build/texture_builder.h"

#include <sys/statvfs.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "build/image_rows.h"
#include "build/mip_kernel.h"
#include "build/noise_value.h"
#include "build/page_set.h"
#include "build/row_ring.h"
#include "common/error.h"
#include "common/progress_bar.h"
#include "common/resource_limits.h"
#include "format/virtual_texture_writer.h"

namespace vt {
namespace {

// Rows a page row needs beyond its own on each side: its border, and the level m rows that make
// the parent texels around its quarter, which its NoiseValue reads (two rows, plus the reach).
uint32_t rowMargin(const TextureDescription& d, const MipKernel& kernel) {
  return std::max(d.border, 2 + kernel.reach());
}

uint32_t ringCapacity(const TextureDescription& d, const MipKernel& kernel) {
  return d.pageSize + 2 * rowMargin(d, kernel) + 2 + 2 * kernel.reach();
}

int64_t clampIndex(int64_t i, uint64_t side) {
  return std::clamp<int64_t>(i, 0, static_cast<int64_t>(side) - 1);
}

void requireFreeSpace(const std::filesystem::path& output, uint64_t bytes, uint64_t keepFree) {
  const std::filesystem::path folder =
      output.has_parent_path() ? output.parent_path() : std::filesystem::path(".");
  struct statvfs info {};
  if (::statvfs(folder.c_str(), &info) != 0)
    throw InputError(output, "cannot query the free space of " + folder.string());
  const uint64_t available = uint64_t{info.f_bavail} * info.f_frsize;
  if (available < bytes || available - bytes < keepFree)
    throw InputError(output,
                     "not enough free disk space: the texture needs " + std::to_string(bytes) +
                         " bytes" +
                         (keepFree ? " and " + std::to_string(keepFree) + " must stay free" : "") +
                         ", " + folder.string() + " has " + std::to_string(available));
}

class Builder {
 public:
  Builder(const Layout& layout, std::vector<uint64_t> stored, VirtualTextureWriter& writer)
      : d_(layout.description),
        kernel_(layout.filter, d_.colorSpace, d_.channels),
        margin_(rowMargin(d_, kernel_)),
        stored_(std::move(stored)),
        writer_(writer) {
    for (uint32_t m = 0; m < d_.levelCount; ++m)
      levels_.push_back({levelSide(d_.pageSize, m),
                         RowRing(levelSide(d_.pageSize, m), d_.channels, ringCapacity(d_, kernel_),
                                 layout.background),
                         {}});
    // Footprints: the texels of each level that some image influences. Level m - 1 texel X reads
    // level m columns 2X - r .. 2X + 1 + r, so [a, b) on level m influences
    // X in [ceil((a - 1 - r) / 2), floor((b - 1 + r) / 2)] on level m - 1. Outside them every
    // level holds the background: the filters keep a constant constant.
    const int64_t r = kernel_.reach();
    for (const Placement& image : layout.images)
      levels_.back().footprints.push_back(
          {static_cast<int64_t>(image.x), static_cast<int64_t>(image.x + image.width),
           static_cast<int64_t>(image.y), static_cast<int64_t>(image.y + image.height)});
    for (uint32_t m = d_.finestLevel(); m > 0; --m) {
      const int64_t coarserSide = static_cast<int64_t>(levels_[m - 1].side);
      const auto lower = [&](int64_t a) { return std::max<int64_t>(0, (a - r) / 2); };
      const auto upper = [&](int64_t b) { return std::min(coarserSide, (b + r + 1) / 2); };
      for (const Footprint& f : levels_[m].footprints)
        levels_[m - 1].footprints.push_back({lower(f.x0), upper(f.x1), lower(f.y0), upper(f.y1)});
    }
  }

  uint64_t ringBytes() const {
    uint64_t bytes = 0;
    for (const Level& level : levels_) bytes += level.rows.bytes();
    return bytes;
  }

  RowRing& finestRows() { return levels_.back().rows; }

  // Called after a row was appended to level m: makes what that row completes.
  void rowAdded(uint32_t m) {
    Level& level = levels_[m];
    const uint64_t q = level.rows.rowsReceived() - 1;
    while (level.nextPageRow * d_.pageSize < level.side) {
      const uint64_t lastNeeded =
          std::min((level.nextPageRow + 1) * d_.pageSize + margin_ - 1, level.side - 1);
      if (q < lastNeeded) break;
      cutPageRow(m, level.nextPageRow++);
    }
    if (m == 0) return;
    Level& coarser = levels_[m - 1];
    const uint32_t reach = kernel_.reach();
    while (coarser.rows.rowsReceived() < coarser.side) {
      const uint64_t r = coarser.rows.rowsReceived();
      if (q < std::min(2 * r + 1 + reach, level.side - 1)) break;
      std::array<const uint8_t*, 4> rows{};
      for (uint32_t k = 0; k < 2 + 2 * reach; ++k)
        rows[k] = level.rows.row(
            static_cast<uint64_t>(clampIndex(static_cast<int64_t>(2 * r + k) - reach, level.side)));
      uint8_t* out = coarser.rows.append(r);
      // Only texels some image influences are computed; the rest is background. Spans are cut
      // into chunks for the threads; each texel is computed alone, so the result does not depend
      // on the split.
      constexpr uint64_t kChunk = 1024;
      for (const ColumnSpan& span : spansOf(coarser, r)) {
        coarser.rows.wrote(span);
        const uint64_t count = span.end - span.begin;
        tbb::parallel_for(uint64_t{0}, (count + kChunk - 1) / kChunk, [&](uint64_t c) {
          const uint64_t begin = span.begin + c * kChunk;
          kernel_.downsample(rows, level.side, begin, std::min(kChunk, span.end - begin), out);
        });
      }
      rowAdded(m - 1);
    }
  }

 private:
  struct Footprint {
    int64_t x0, x1, y0, y1;  // half-open texel rectangle
  };
  struct Level {
    uint64_t side;
    RowRing rows;
    std::vector<Footprint> footprints;
    uint64_t nextPageRow = 0;
  };

  // Column spans of row y of a level that footprints cover, merged, in increasing order.
  static std::vector<ColumnSpan> spansOf(const Level& level, uint64_t y) {
    std::vector<ColumnSpan> spans;
    for (const Footprint& f : level.footprints)
      if (static_cast<int64_t>(y) >= f.y0 && static_cast<int64_t>(y) < f.y1)
        spans.push_back({static_cast<uint64_t>(f.x0), static_cast<uint64_t>(f.x1)});
    std::sort(spans.begin(), spans.end(),
              [](const ColumnSpan& a, const ColumnSpan& b) { return a.begin < b.begin; });
    std::vector<ColumnSpan> merged;
    for (const ColumnSpan& span : spans) {
      if (!merged.empty() && span.begin <= merged.back().end)
        merged.back().end = std::max(merged.back().end, span.end);
      else
        merged.push_back(span);
    }
    return merged;
  }

  void cutPageRow(uint32_t m, uint64_t py) {
    const auto first = std::lower_bound(stored_.begin(), stored_.end(),
                                        absoluteIndex(PageId{0, static_cast<uint32_t>(py), m}));
    const auto last =
        std::upper_bound(first, stored_.end(),
                         absoluteIndex(PageId{static_cast<uint32_t>(pagesPerSide(m) - 1),
                                              static_cast<uint32_t>(py), m}));
    const size_t begin = static_cast<size_t>(first - stored_.begin());
    const size_t end = static_cast<size_t>(last - stored_.begin());
    tbb::parallel_for(begin, end, [&](size_t k) { cutPage(fromAbsoluteIndex(stored_[k])); });
  }

  // The stored page: level texel (px P - B + i, py P - B + j), clamped to the level.
  void cutPage(PageId page) const {
    const Level& level = levels_[page.level];
    const uint32_t side = d_.storedPageSide();
    const uint32_t c = d_.channels;
    std::vector<std::byte> texels(d_.pageBytes());
    const int64_t x0 = int64_t{page.x} * d_.pageSize - d_.border;
    const int64_t y0 = int64_t{page.y} * d_.pageSize - d_.border;
    for (uint32_t j = 0; j < side; ++j) {
      const uint8_t* row = level.rows.row(static_cast<uint64_t>(clampIndex(y0 + j, level.side)));
      std::byte* out = texels.data() + size_t{j} * side * c;
      for (uint32_t i = 0; i < side; ++i) {
        const uint64_t x = static_cast<uint64_t>(clampIndex(x0 + i, level.side));
        for (uint32_t k = 0; k < c; ++k) out[size_t{i} * c + k] = std::byte(row[x * c + k]);
      }
    }
    const float noise = page.level == 0 ? 0.0f : noiseValue(d_, page, texels, parentTexels(page));
    writer_.writePage(page, texels, noise);
  }

  // The texels of the parent's stored page that noiseValue reads for `page` (its quarter and one
  // texel around it, clamped to the stored page), computed from this level's rows with the mip
  // kernel, so they equal the parent page's own texels. The rest of the page stays zero.
  std::vector<std::byte> parentTexels(PageId page) const {
    const Level& level = levels_[page.level];
    const uint64_t parentSide = level.side / 2;
    const PageId up = parent(page);
    const int64_t side = d_.storedPageSide(), half = d_.pageSize / 2, B = d_.border;
    const int64_t qx = (page.x & 1) * half, qy = (page.y & 1) * half;
    const int64_t parentX0 = int64_t{up.x} * d_.pageSize - B;
    const int64_t parentY0 = int64_t{up.y} * d_.pageSize - B;
    std::vector<std::byte> texels(d_.pageBytes());
    const uint32_t reach = kernel_.reach();
    for (int64_t sy = std::max<int64_t>(B + qy - 1, 0); sy <= std::min(B + qy + half, side - 1);
         ++sy) {
      const int64_t Y = clampIndex(parentY0 + sy, parentSide);
      MipKernel::Rows rows{};
      for (uint32_t k = 0; k < 2 + 2 * reach; ++k)
        rows[k] = level.rows.row(static_cast<uint64_t>(clampIndex(2 * Y + k - reach, level.side)));
      for (int64_t sx = std::max<int64_t>(B + qx - 1, 0); sx <= std::min(B + qx + half, side - 1);
           ++sx) {
        const int64_t X = clampIndex(parentX0 + sx, parentSide);
        kernel_.texel(rows, static_cast<uint64_t>(X), level.side,
                      reinterpret_cast<uint8_t*>(texels.data()) + (sy * side + sx) * d_.channels);
      }
    }
    return texels;
  }

  const TextureDescription& d_;
  MipKernel kernel_;
  uint32_t margin_;
  std::vector<uint64_t> stored_;
  VirtualTextureWriter& writer_;
  std::vector<Level> levels_;
};

}  // namespace

uint64_t ringBytesBound(const TextureDescription& d, MipFilter filter) {
  const MipKernel kernel(filter, d.colorSpace, d.channels);
  return 2 * uint64_t{ringCapacity(d, kernel)} * d.sideTexels() * d.channels;
}

BuildReport buildVirtualTexture(const Layout& layout, const std::filesystem::path& output,
                                const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const TextureDescription& d = layout.description;
  // Memory first, then pages and disk: each refused before anything is allocated for it.
  if (const uint64_t ringBytes = ringBytesBound(d, layout.filter); ringBytes > kMaxBuildRingBytes)
    throw limitError(layout.source,
                     "building a " + std::to_string(d.sideTexels()) + "^2-texel texture (" +
                         std::to_string(d.channels) + " channels, page size " +
                         std::to_string(d.pageSize) + ", " + toString(layout.filter) + " filter)",
                     ringBytes, kMaxBuildRingBytes, " bytes of row rings");
  std::vector<uint64_t> stored = storedPages(layout);
  const bool sparse = stored.size() < d.totalPages();
  BuildReport report;
  report.storedPages = stored.size();
  report.totalPages = d.totalPages();
  report.fileBytes = layoutFor(d, sparse, stored.size()).fileBytes;
  requireFreeSpace(output, report.fileBytes, options.keepFreeBytes);

  const unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                        std::max(1u, threads));
  VirtualTextureWriter writer =
      sparse ? VirtualTextureWriter(output, d, stored) : VirtualTextureWriter(output, d);
  Builder builder(layout, std::move(stored), writer);
  ImageRows images(layout);
  report.ringBytes = builder.ringBytes();
  {
    ProgressBar progress("vt build", d.sideTexels(), options.progress);
    for (uint64_t y = 0; y < d.sideTexels(); ++y) {
      images.row(y, builder.finestRows());
      report.scanlineBytes = std::max(report.scanlineBytes, images.bufferBytes());
      builder.rowAdded(d.finestLevel());
      progress.update(y + 1);
    }
  }
  writer.commit();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace vt
