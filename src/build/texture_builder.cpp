#include "build/texture_builder.h"

#include <sys/statvfs.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "build/ancestor_error.h"
#include "build/block_encoding.h"
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

// The texels of a level that some image influences: a half-open rectangle per image per level.
struct Footprint {
  int64_t x0, x1, y0, y1;
};

// Footprints per level. Level m - 1 texel X reads level m columns 2X - r .. 2X + 1 + r, so [a, b)
// on level m influences X in [ceil((a - 1 - r) / 2), floor((b - 1 + r) / 2)] on level m - 1.
// Outside them every level holds the background: the filters keep a constant constant.
std::vector<std::vector<Footprint>> levelFootprints(const Layout& layout, uint32_t reach) {
  const TextureDescription& d = layout.description;
  std::vector<std::vector<Footprint>> levels(d.levelCount);
  for (const Placement& image : layout.images)
    levels.back().push_back(
        {static_cast<int64_t>(image.x), static_cast<int64_t>(image.x + image.width),
         static_cast<int64_t>(image.y), static_cast<int64_t>(image.y + image.height)});
  const int64_t r = reach;
  for (uint32_t m = d.finestLevel(); m > 0; --m) {
    const auto coarserSide = static_cast<int64_t>(levelSide(d.pageSize, m - 1));
    const auto lower = [&](int64_t a) { return std::max<int64_t>(0, (a - r) / 2); };
    const auto upper = [&](int64_t b) { return std::min(coarserSide, (b + r + 1) / 2); };
    for (const Footprint& f : levels[m])
      levels[m - 1].push_back({lower(f.x0), upper(f.x1), lower(f.y0), upper(f.y1)});
  }
  return levels;
}

// The largest sum of the weights of rectangles' row ranges [from, to) that share a row.
uint64_t largestSumAtOneRow(std::vector<std::pair<int64_t, int64_t>> changes) {
  std::sort(changes.begin(), changes.end());  // at one row, endings (negative) first
  int64_t sum = 0, largest = 0;
  for (const auto& [row, change] : changes) largest = std::max(largest, sum += change);
  return static_cast<uint64_t>(largest);
}

// The most strips (row_ring.h) a level's ring holds at once. A strip lives from a row that
// writes into it until `capacity` rows later, so at row q it can only be one of a footprint with
// y0 <= q < y1 + capacity: the largest sum of such footprints' strips, at most the level's.
uint64_t mostStrips(const std::vector<Footprint>& footprints, uint64_t capacity, uint64_t side) {
  constexpr uint64_t kStrip = RowRing::kStripTexels;
  std::vector<std::pair<int64_t, int64_t>> changes;  // (row, strips added from it on)
  for (const Footprint& f : footprints) {
    if (f.x0 >= f.x1 || f.y0 >= f.y1) continue;
    const auto strips = static_cast<int64_t>(static_cast<uint64_t>(f.x1 - 1) / kStrip -
                                             static_cast<uint64_t>(f.x0) / kStrip + 1);
    changes.emplace_back(f.y0, strips);
    changes.emplace_back(f.y1 + static_cast<int64_t>(capacity), -strips);
  }
  return std::min(largestSumAtOneRow(std::move(changes)), (side + kStrip - 1) / kStrip);
}

// The most footprints crossing one row: a bound on the spans one row writes.
uint64_t mostCrossing(const std::vector<Footprint>& footprints) {
  std::vector<std::pair<int64_t, int64_t>> changes;
  for (const Footprint& f : footprints) {
    changes.emplace_back(f.y0, 1);
    changes.emplace_back(f.y1, -1);
  }
  return largestSumAtOneRow(std::move(changes));
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
                         {},
                         0,
                         0,
                         {}});
    std::vector<std::vector<Footprint>> footprints = levelFootprints(layout, kernel_.reach());
    for (uint32_t m = 0; m < d_.levelCount; ++m) {
      std::sort(footprints[m].begin(), footprints[m].end(),
                [](const Footprint& a, const Footprint& b) { return a.y0 < b.y0; });
      levels_[m].footprints = std::move(footprints[m]);
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
      std::array<uint64_t, 4> sourceRows{};
      for (uint32_t k = 0; k < 2 + 2 * reach; ++k)
        sourceRows[k] =
            static_cast<uint64_t>(clampIndex(static_cast<int64_t>(2 * r + k) - reach, level.side));
      coarser.rows.append(r);
      // Only texels some image influences are computed; the rest is background. Spans are cut at
      // the strips of the coarser ring for the threads; each texel is computed alone, so the
      // result does not depend on the split.
      constexpr uint64_t kStrip = RowRing::kStripTexels;
      for (const ColumnSpan& span : spansOf(coarser, r)) {
        coarser.rows.declare(span);
        tbb::parallel_for(span.begin / kStrip, (span.end - 1) / kStrip + 1, [&](uint64_t strip) {
          const uint64_t begin = std::max(span.begin, strip * kStrip);
          const uint64_t end = std::min(span.end, (strip + 1) * kStrip);
          const SourceColumns source(level, sourceRows, 2 + 2 * reach, 2 * begin, 2 * end, reach);
          kernel_.downsample(source.rows, level.side, begin, end - begin,
                             coarser.rows.writable(begin), source.first);
        });
      }
      rowAdded(m - 1);
    }
  }

 private:
  struct Level {
    uint64_t side;
    RowRing rows;
    std::vector<Footprint> footprints;  // by first row
    uint64_t nextPageRow = 0;
    size_t nextFootprint = 0;           // the first footprint not yet reached by the rows
    std::vector<Footprint> crossing;    // footprints reached and not yet passed
  };

  // Columns [x0 - reach, x1 + reach) of `count` held rows of a level, clamped to the level and
  // copied out of its ring, as the mip kernel reads them.
  struct SourceColumns {
    SourceColumns(const Level& level, const std::array<uint64_t, 4>& rowIndices, uint32_t count,
                  uint64_t x0, uint64_t x1, uint32_t reach)
        : first(x0 >= reach ? x0 - reach : 0),
          width(std::min(x1 + reach, level.side) - first),
          texels(count * width * level.rows.channels()) {
      for (uint32_t k = 0; k < count; ++k) {
        uint8_t* row = texels.data() + k * width * level.rows.channels();
        level.rows.read(rowIndices[k], first, width, row);
        rows[k] = row;
      }
    }
    uint64_t first, width;
    std::vector<uint8_t> texels;
    MipKernel::Rows rows{};
  };

  // Column spans of row y of a level that footprints cover, merged, in increasing order. Rows are
  // asked in increasing order; only the footprints crossing the row are looked at.
  static std::vector<ColumnSpan> spansOf(Level& level, uint64_t y) {
    const auto row = static_cast<int64_t>(y);
    std::erase_if(level.crossing, [row](const Footprint& f) { return f.y1 <= row; });
    while (level.nextFootprint < level.footprints.size() &&
           level.footprints[level.nextFootprint].y0 <= row)
      level.crossing.push_back(level.footprints[level.nextFootprint++]);
    std::vector<ColumnSpan> spans;
    for (const Footprint& f : level.crossing)
      if (row >= f.y0 && row < f.y1)
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
    // The level's columns the page reads, [first, first + width): x0 .. x0 + side - 1 clamped.
    const auto first = static_cast<uint64_t>(clampIndex(x0, level.side));
    const uint64_t width = static_cast<uint64_t>(clampIndex(x0 + side - 1, level.side)) - first + 1;
    std::vector<uint8_t> row(width * c);
    for (uint32_t j = 0; j < side; ++j) {
      level.rows.read(static_cast<uint64_t>(clampIndex(y0 + j, level.side)), first, width,
                      row.data());
      std::byte* out = texels.data() + size_t{j} * side * c;
      for (uint32_t i = 0; i < side; ++i) {
        const uint64_t x = static_cast<uint64_t>(clampIndex(x0 + i, level.side)) - first;
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
      std::array<uint64_t, 4> sourceRows{};
      for (uint32_t k = 0; k < 2 + 2 * reach; ++k)
        sourceRows[k] = static_cast<uint64_t>(clampIndex(2 * Y + k - reach, level.side));
      const int64_t sx0 = std::max<int64_t>(B + qx - 1, 0);
      const int64_t sx1 = std::min(B + qx + half, side - 1);
      const auto X0 = static_cast<uint64_t>(clampIndex(parentX0 + sx0, parentSide));
      const auto X1 = static_cast<uint64_t>(clampIndex(parentX0 + sx1, parentSide));
      const SourceColumns source(level, sourceRows, 2 + 2 * reach, 2 * X0, 2 * X1 + 2, reach);
      for (int64_t sx = sx0; sx <= sx1; ++sx) {
        const int64_t X = clampIndex(parentX0 + sx, parentSide);
        kernel_.texel(source.rows, static_cast<uint64_t>(X), level.side,
                      reinterpret_cast<uint8_t*>(texels.data()) + (sy * side + sx) * d_.channels,
                      source.first);
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

uint64_t ringBytesBound(const Layout& layout) {
  const TextureDescription& d = layout.description;
  const MipKernel kernel(layout.filter, d.colorSpace, d.channels);
  const uint64_t capacity = ringCapacity(d, kernel);
  // Per strip its texels and at most `capacity` retirement entries (row_ring.h); per level the
  // column table; per slot the written spans, at most one per footprint crossing its row.
  const uint64_t stripBytes =
      capacity * (RowRing::kStripTexels * d.channels + sizeof(std::pair<uint32_t, uint64_t>));
  const std::vector<std::vector<Footprint>> footprints = levelFootprints(layout, kernel.reach());
  uint64_t bytes = 0;
  for (uint32_t m = 0; m < d.levelCount; ++m) {
    const uint64_t side = levelSide(d.pageSize, m);
    bytes += mostStrips(footprints[m], capacity, side) * stripBytes +
             (side + RowRing::kStripTexels - 1) / RowRing::kStripTexels * sizeof(uint32_t) +
             capacity * mostCrossing(footprints[m]) * sizeof(ColumnSpan);
  }
  return bytes;
}

BuildReport buildVirtualTexture(const Layout& layout, const std::filesystem::path& output,
                                const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const TextureDescription& d = layout.description;
  // Memory first, then pages and disk: each refused before anything is allocated for it.
  if (const uint64_t ringBytes = ringBytesBound(layout); ringBytes > kMaxBuildRingBytes)
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
  report.fileBytes = layoutFor(d, sparse, stored.size(), options.ancestorErrors).fileBytes;
  requireFreeSpace(output, report.fileBytes, options.keepFreeBytes);

  const unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                        std::max(1u, threads));
  VirtualTextureWriter writer =
      sparse ? VirtualTextureWriter(output, d, stored, BlockEncoder(encodeBlocks))
             : VirtualTextureWriter(output, d, BlockEncoder(encodeBlocks));
  Builder builder(layout, std::move(stored), writer);
  ImageRows images(layout);
  {
    ProgressBar progress("vt build", d.sideTexels(), options.progress);
    for (uint64_t y = 0; y < d.sideTexels(); ++y) {
      images.row(y, builder.finestRows());
      report.scanlineBytes = std::max(report.scanlineBytes, images.bufferBytes());
      builder.rowAdded(d.finestLevel());
      progress.update(y + 1);
    }
  }
  report.ringBytes = builder.ringBytes();  // strips are pooled, never freed: the most held
  if (options.ancestorErrors) {
    const auto ancestorStart = std::chrono::steady_clock::now();
    writer.setAncestorErrors(ancestorErrorsOfWrittenPages(writer));
    report.ancestorErrorSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - ancestorStart).count();
  }
  writer.commit();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace vt
