#include "format/texture_report.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <sstream>

#include "common/checksum.h"

namespace vt {
namespace {

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

// Per distance d (levels up), the mean and largest error of the stored pages shown through their
// ancestor d levels up.
nlohmann::json ancestorErrorReport(const VirtualTextureReader& reader) {
  const uint32_t levels = reader.description().levelCount;
  std::vector<double> sum(levels, 0.0), maximum(levels, 0.0);
  std::vector<uint64_t> pages(levels, 0);
  for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot) {
    const PageId page = fromAbsoluteIndex(reader.storedPage(slot));
    const std::span<const float> errors = reader.ancestorErrors(page);
    for (uint32_t l = 0; l < page.level; ++l) {
      const uint32_t up = page.level - l;
      sum[up] += errors[l];
      maximum[up] = std::max(maximum[up], static_cast<double>(errors[l]));
      ++pages[up];
    }
  }
  nlohmann::json byDistance = nlohmann::json::array();
  for (uint32_t up = 1; up < levels; ++up)
    byDistance.push_back({{"levels_up", up},
                          {"pages", pages[up]},
                          {"mean", pages[up] ? sum[up] / static_cast<double>(pages[up]) : 0.0},
                          {"max", maximum[up]}});
  return byDistance;
}

}  // namespace

nlohmann::json textureReport(const VirtualTextureReader& reader) {
  const TextureDescription& d = reader.description();
  nlohmann::json report;
  report["file"] = reader.path().string();
  report["format_version"] = fileVersionOf(d.format, reader.hasAncestorErrors());
  report["identity"] = "xxh3:" + checksumText(reader.identity());
  report["file_bytes"] = reader.fileBytes();
  report["page_size"] = d.pageSize;
  report["border"] = d.border;
  report["stored_page_side"] = d.storedPageSide();
  // A page as the file holds it; a block format's pages are read decoded, larger.
  report["page_bytes"] = d.storedPageBytes();
  if (isBlockCompressed(d.format)) report["decoded_page_bytes"] = d.pageBytes();
  report["levels"] = d.levelCount;
  report["side_texels"] = d.sideTexels();
  report["channels"] = d.channels;
  report["pixel_format"] = toString(d.format);
  report["color_space"] = toString(d.colorSpace);
  report["sparse"] = reader.isSparse();
  report["stored_pages"] = reader.storedPageCount();
  report["total_pages"] = d.totalPages();

  const std::vector<uint64_t> stored = reader.storedPagesPerLevel();
  nlohmann::json levels = nlohmann::json::array();
  for (uint32_t m = 0; m < d.levelCount; ++m)
    levels.push_back({{"level", m},
                      {"side_texels", levelSide(d.pageSize, m)},
                      {"pages", pagesInLevel(m)},
                      {"stored_pages", stored[m]}});
  report["per_level"] = levels;

  // NoiseValues of every stored page but the root, which has no parent to improve on.
  double sum = 0.0, maximum = 0.0;
  const auto noise = reader.noiseValues();
  for (size_t k = 1; k < noise.size(); ++k) {
    sum += noise[k];
    maximum = std::max(maximum, static_cast<double>(noise[k]));
  }
  const size_t counted = noise.size() - 1;
  report["noise_values"] = {{"pages", counted},
                            {"mean", counted ? sum / static_cast<double>(counted) : 0.0},
                            {"max", maximum}};
  if (reader.hasAncestorErrors()) report["ancestor_errors"] = ancestorErrorReport(reader);
  return report;
}

std::string formatTextureReport(const nlohmann::json& r) {
  std::ostringstream out;
  const auto line = [&](const char* label, const std::string& text) {
    char padded[16];
    std::snprintf(padded, sizeof padded, "%-13s", label);
    out << padded << text << '\n';
  };
  const auto str = [](const nlohmann::json& value) {
    return value.is_string() ? value.get<std::string>() : value.dump();
  };
  line("file", str(r["file"]));
  line("format", "virtual texture v" + str(r["format_version"]) + ", " + str(r["channels"]) +
                     " x " + str(r["pixel_format"]) + ", " + str(r["color_space"]) + ", " +
                     (r["sparse"].get<bool>() ? "sparse" : "dense"));
  line("identity", str(r["identity"]));
  line("pages", str(r["page_size"]) + "^2 texels + " + str(r["border"]) +
                    " border = " + str(r["stored_page_side"]) + "^2 stored, " +
                    str(r["page_bytes"]) + " bytes each" +
                    (r.contains("decoded_page_bytes")
                         ? " (" + str(r["decoded_page_bytes"]) + " decoded)"
                         : std::string()));
  const uint32_t levels = r["levels"].get<uint32_t>();
  line("texture", str(r["side_texels"]) + " x " + str(r["side_texels"]) + " texels, levels 0.." +
                      std::to_string(levels - 1) + " (0 coarsest)");
  line("stored", str(r["stored_pages"]) + " of " + str(r["total_pages"]) + " pages, " +
                     str(r["file_bytes"]) + " bytes");
  out << "level   side texels        pages       stored\n";
  for (const auto& level : r["per_level"]) {
    char row[96];
    std::snprintf(row, sizeof row, "%5u %13" PRIu64 " %12" PRIu64 " %12" PRIu64 "\n",
                  level["level"].get<uint32_t>(), level["side_texels"].get<uint64_t>(),
                  level["pages"].get<uint64_t>(), level["stored_pages"].get<uint64_t>());
    out << row;
  }
  const auto& noise = r["noise_values"];
  line("NoiseValues", "mean " + fixed(noise["mean"].get<double>(), 5) + ", max " +
                          fixed(noise["max"].get<double>(), 5) + " over " + str(noise["pages"]) +
                          " pages (luminance RMSE against the parent)");
  if (r.contains("ancestor_errors")) {
    std::string means;
    for (const auto& e : r["ancestor_errors"])
      means += (means.empty() ? "" : ", ") + str(e["levels_up"]) + " up " +
               fixed(e["mean"].get<double>(), 5);
    line("AncestorErr", "mean 1 - SSIM through the ancestor " + means + " (8 x 8 windows)");
  }
  if (r.contains("verified_pages"))
    line("verified", str(r["verified_pages"]) + " pages read, every checksum matches");
  return out.str();
}

uint64_t verifyAllPages(const VirtualTextureReader& reader) {
  std::vector<std::byte> page(reader.description().pageBytes());
  for (uint64_t slot = 0; slot < reader.storedPageCount(); ++slot)
    reader.readPage(fromAbsoluteIndex(reader.storedPage(slot)), page);
  return reader.storedPageCount();
}

}  // namespace vt
