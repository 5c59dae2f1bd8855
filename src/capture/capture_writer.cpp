#include "capture/capture_writer.h"

#include <span>
#include <stdexcept>

#include "common/checksum.h"
#include "common/posix_file.h"
#include "format/page_address.h"

namespace vt::capture {
namespace {

// Rows bottom to top (GL) to top to bottom (files).
template <class T>
std::vector<T> topToBottom(const std::vector<T>& rows, size_t width, size_t height) {
  std::vector<T> flipped(rows.size());
  for (size_t y = 0; y < height; ++y)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(y * width), width,
                flipped.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * width));
  return flipped;
}

template <class T>
void writeData(const std::filesystem::path& file, const std::vector<T>& values) {
  writeFileAtomically(file, std::as_bytes(std::span(values)));
}

}  // namespace

void writeCapturedFrame(const std::filesystem::path& manifest, const CapturedFrame& c) {
  const Viewport v = c.frame->viewport;
  const auto width = static_cast<size_t>(v.width), height = static_cast<size_t>(v.height);
  const std::filesystem::path folder = manifest.parent_path();
  const std::string stem = manifest.stem().string();

  const std::string identity = checksumText(c.textureIdentity);
  nlohmann::ordered_json root = {
      {"format", "vt-capture"},
      {"version", 1},
      {"renderer", c.renderer},
      {"texture", {{"file", c.textureFile}, {"identity", identity}}},
      {"viewport", {{"width", v.width}, {"height", v.height}}},
      {"needbuffer_encoding", c.need8 ? "need8" : "need32"},
      {"filtering", c.trilinear ? "trilinear" : "bilinear"},
      {"sampling", c.exactFilter ? "texel_fetch" : "hardware_linear"}};

  std::vector<float> vertices;
  for (const ClipVertex& x : c.mesh->vertices)
    vertices.insert(vertices.end(), {x.position.x, x.position.y, x.position.z, x.position.w,
                                     x.uv.x, x.uv.y});
  writeData(folder / (stem + ".vertices.f32"), vertices);
  writeData(folder / (stem + ".indices.u32"), c.mesh->indices);
  root["geometry"] = {{"vertices", stem + ".vertices.f32"},
                      {"vertex_count", c.mesh->vertices.size()},
                      {"indices", stem + ".indices.u32"},
                      {"index_count", c.mesh->indices.size()}};

  nlohmann::json pages = nlohmann::json::array();
  for (const uint64_t index : c.cache->residentPages) {
    const PageId page = fromAbsoluteIndex(index);
    const glm::u16vec4 entry = c.cache->indirection.entry(page);
    pages.push_back({page.level, page.x, page.y, entry.x, entry.y});
  }
  root["cache"] = {{"all_resident", false},
                   {"frames_x", c.cache->framesX},
                   {"frames_y", c.cache->framesY},
                   {"pages", pages}};

  root["color"] = stem + ".color.rgba8";
  writeData(folder / (stem + ".color.rgba8"), topToBottom(c.frame->color, width * 4, height));
  const std::vector<glm::uvec4> need = topToBottom(c.frame->need, width, height);
  if (c.need8) {
    std::vector<uint8_t> bytes;
    bytes.reserve(need.size() * 4);
    for (const glm::uvec4& n : need)
      for (int k = 0; k < 4; ++k) {
        if (n[k] > 255) throw std::runtime_error(manifest.string() + ": need8 value above 255");
        bytes.push_back(static_cast<uint8_t>(n[k]));
      }
    root["needbuffer"] = stem + ".need.rgba8";
    writeData(folder / (stem + ".need.rgba8"), bytes);
  } else {
    root["needbuffer"] = stem + ".need.u32";
    writeData(folder / (stem + ".need.u32"), need);
  }
  if (!c.extra.is_null()) root["extra"] = c.extra;
  writeFileAtomically(manifest, root.dump(1) + "\n");  // last: it names complete files only
}

}  // namespace vt::capture
