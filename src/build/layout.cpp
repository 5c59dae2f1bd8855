#include "build/layout.h"

#include <algorithm>
#include <bit>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <queue>

#include "common/error.h"
#include "common/image_file.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/resource_limits.h"

namespace vt {
namespace {

using nlohmann::json;

// Fills the image's own size and channels and, where no region gave them, the placed size.
void setImage(Placement& placement, const ImageInfo& image, std::optional<uint32_t> width,
              std::optional<uint32_t> height) {
  placement.imageWidth = image.width;
  placement.imageHeight = image.height;
  placement.channels = image.channels;
  placement.width = width.value_or(image.width);
  placement.height = height.value_or(image.height);
}

uint64_t unsignedField(const json& object, const char* key, const std::filesystem::path& file,
                       const std::string& where) {
  const json& value = object.at(key);
  if (!value.is_number_unsigned())
    throw InputError(
        file, where + "field " + key + ": " + value.dump() + " is not a non-negative integer");
  return value.get<uint64_t>();
}

// An optional placed width or height: [1, kMaxPlacedSide].
std::optional<uint32_t> placedSideField(const json& entry, const char* key,
                                        const std::filesystem::path& file,
                                        const std::string& where) {
  if (!entry.contains(key)) return std::nullopt;
  const uint64_t value = unsignedField(entry, key, file, where);
  if (value < 1 || value > kMaxPlacedSide)
    throw InputError(file, where + "field " + key + ": " + std::to_string(value) +
                               " is not in [1, " + std::to_string(kMaxPlacedSide) +
                               "] (the format's widest texture)");
  return static_cast<uint32_t>(value);
}

// An optional source offset: an integer in [-2^40, 2^40].
std::optional<int64_t> sourceOffsetField(const json& entry, const char* key,
                                         const std::filesystem::path& file,
                                         const std::string& where) {
  if (!entry.contains(key)) return std::nullopt;
  const json& value = entry.at(key);
  const bool valid = value.is_number_unsigned()
                         ? value.get<uint64_t>() <= static_cast<uint64_t>(kMaxSourceOffset)
                         : value.is_number_integer() && value.get<int64_t>() >= -kMaxSourceOffset;
  if (!valid)
    throw InputError(
        file, where + "field " + key + ": " + value.dump() + " is not an integer in [-2^40, 2^40]");
  return value.get<int64_t>();
}

// at + size, saturated: x and y are any 64-bit value of the file.
uint64_t endOf(uint64_t at, uint32_t size) {
  return at > UINT64_MAX - size ? UINT64_MAX : at + size;
}

// Throws when two placements overlap. Sweep along x: the placements crossing the sweep line are
// disjoint in y (else we had thrown), so a new one can only overlap its neighbours in y order.
// O(n log n) for the thousands of faces a retextured map places.
void requireNoOverlap(const Layout& layout) {
  const std::vector<Placement>& images = layout.images;
  std::vector<size_t> order(images.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::pair(images[a].x, a) < std::pair(images[b].x, b);
  });
  std::map<uint64_t, size_t> crossing;        // top row -> placement crossing the sweep line
  using End = std::pair<uint64_t, uint64_t>;  // (end column, top row)
  std::priority_queue<End, std::vector<End>, std::greater<>> ends;
  const auto overlap = [&](size_t a, size_t b) {
    throw InputError(layout.source, "images " + images[a].file.string() + " and " +
                                        images[b].file.string() + " overlap (images[" +
                                        std::to_string(a) + "] and images[" + std::to_string(b) +
                                        "])");
  };
  for (const size_t i : order) {
    const Placement& p = images[i];
    while (!ends.empty() && ends.top().first <= p.x) {
      crossing.erase(ends.top().second);
      ends.pop();
    }
    const auto below = crossing.lower_bound(p.y);
    if (below != crossing.end() && below->first < p.y + p.height) overlap(below->second, i);
    if (below != crossing.begin()) {
      const size_t above = std::prev(below)->second;
      if (images[above].y + images[above].height > p.y) overlap(above, i);
    }
    crossing.emplace(p.y, i);
    ends.emplace(p.x + p.width, p.y);
  }
}

uint32_t smallField(const json& object, const char* key, const std::filesystem::path& file) {
  const uint64_t value = unsignedField(object, key, file, "");
  if (value > 0xffffffffu)
    throw InputError(file,
                     std::string("field ") + key + ": " + std::to_string(value) + " is too large");
  return static_cast<uint32_t>(value);
}

// Completes the description from the images and checks everything against the format's limits.
void finish(Layout& layout, std::optional<uint64_t> side, std::optional<uint32_t> channels) {
  TextureDescription& d = layout.description;
  const std::filesystem::path& file = layout.source;
  if (layout.images.empty()) throw InputError(file, "the layout places no images");
  if (channels) {
    d.channels = *channels;
  } else if (isBlockCompressed(d.format)) {
    d.channels = 4;  // blocks hold RGBA
  } else {
    d.channels = 0;
    for (const Placement& image : layout.images) d.channels = std::max(d.channels, image.channels);
    d.channels = std::min(d.channels, kMaxChannels);
  }
  d.levelCount = 1;  // checked with the other fields below, before the side is derived
  if (const auto problem = findProblem(d))
    throw InputError(file, "field " + problem->field + ": " + problem->problem);

  uint64_t extent = 0;
  for (const Placement& image : layout.images)
    extent = std::max({extent, endOf(image.x, image.width), endOf(image.y, image.height)});
  const uint64_t wanted = side.value_or(std::max<uint64_t>(extent, d.pageSize));
  const uint64_t maxSide = levelSide(d.pageSize, kMaxLevel);
  if (wanted > maxSide)
    throw InputError(file, "the texture would be " + std::to_string(wanted) +
                               " texels wide, beyond the format's limit of " +
                               std::to_string(maxSide) + " (page size " +
                               std::to_string(d.pageSize) + " times 2^" +
                               std::to_string(kMaxLevel) + ")");
  uint32_t finest = 0;
  while (levelSide(d.pageSize, finest) < wanted) ++finest;
  if (side && levelSide(d.pageSize, finest) != *side)
    throw InputError(file, "field side: " + std::to_string(*side) + " is not the page size " +
                               std::to_string(d.pageSize) + " times a power of two");
  d.levelCount = finest + 1;
  const uint64_t textureSide = d.sideTexels();

  for (size_t i = 0; i < layout.images.size(); ++i) {
    const Placement& image = layout.images[i];
    if (endOf(image.x, image.width) > textureSide || endOf(image.y, image.height) > textureSide)
      throw InputError(file, "image " + image.file.string() + " (" + std::to_string(image.width) +
                                 " x " + std::to_string(image.height) + " at " +
                                 std::to_string(image.x) + ", " + std::to_string(image.y) +
                                 ") reaches outside the texture of " + std::to_string(textureSide) +
                                 " x " + std::to_string(textureSide) + " texels (images[" +
                                 std::to_string(i) + "])");
  }

  // A region placement's image is decoded whole (image_rows.h), in the larger of its own and the
  // texture's channels.
  for (size_t i = 0; i < layout.images.size(); ++i) {
    const Placement& image = layout.images[i];
    const uint64_t bytes =
        uint64_t{image.imageWidth} * image.imageHeight * std::max(image.channels, d.channels);
    if (image.region && bytes > kMaxWholeImageBytes)
      throw limitError(image.file,
                       "decoding the " + std::to_string(image.imageWidth) + " x " +
                           std::to_string(image.imageHeight) + " image whole for the region of " +
                           file.string() + " images[" + std::to_string(i) + "]",
                       bytes, kMaxWholeImageBytes, " bytes");
  }

  requireNoOverlap(layout);
}

}  // namespace

ImageInfo probeImageFile(const std::filesystem::path& file, const std::string& namedBy) {
  if (!std::filesystem::exists(file) && file.native().find('\0') == std::string::npos)
    throw InputError(file, "image not found (named by " + namedBy + ")");
  requireRegularFile(file, "image (named by " + namedBy + ")");
  std::string error;
  const std::optional<ImageHeader> header = readImageHeader(file, &error);
  if (!header) throw InputError(file, "cannot read image (named by " + namedBy + "): " + error);
  if (header->width <= 0 || header->height <= 0 || header->channels <= 0)
    throw InputError(file, "image has no texels");
  return {static_cast<uint32_t>(header->width), static_cast<uint32_t>(header->height),
          static_cast<uint32_t>(header->channels)};
}

Layout readLayout(const std::filesystem::path& file, const LayoutOverrides& overrides) {
  return parseLayout(readTextFile(file, "layout file"), file, overrides, probeImageFile);
}

Layout parseLayout(std::string_view text, const std::filesystem::path& file,
                   const LayoutOverrides& overrides, const ImageProbe& probe) {
  json root;
  try {
    root = parseJsonText(text, file);
  } catch (const json::exception& e) {
    throw InputError(file, "not valid JSON: " + jsonErrorText(e));
  }
  if (!root.is_object()) throw InputError(file, "the layout is not a JSON object");

  Layout layout;
  layout.source = file;
  TextureDescription& d = layout.description;
  try {
    d.pageSize = overrides.pageSize.value_or(
        root.contains("page_size") ? smallField(root, "page_size", file) : 128);
    d.border =
        overrides.border.value_or(root.contains("border") ? smallField(root, "border", file) : 4);
    d.colorSpace = overrides.colorSpace.value_or(
        parseColorSpace(root.value("color_space", std::string("srgb"))));
    layout.filter =
        overrides.filter.value_or(parseMipFilter(root.value("filter", std::string("box"))));
    d.format =
        overrides.format.value_or(parsePageFormat(root.value("format", std::string("rgba8"))));
    if (root.contains("background")) {
      const json& background = root["background"];
      if (!background.is_array() || background.size() != 4)
        throw InputError(file, "field background: expected 4 integers in [0, 255]");
      for (size_t c = 0; c < 4; ++c) {
        if (!background[c].is_number_unsigned() || background[c].get<uint64_t>() > 255)
          throw InputError(file, "field background: expected 4 integers in [0, 255]");
        layout.background[c] = background[c].get<uint8_t>();
      }
    }
    std::optional<uint64_t> side = overrides.side;
    if (!side && root.contains("side")) side = unsignedField(root, "side", file, "");
    std::optional<uint32_t> channels = overrides.channels;
    if (!channels && root.contains("channels")) channels = smallField(root, "channels", file);

    if (!root.contains("images") || !root["images"].is_array())
      throw InputError(file, "field images: expected an array of {file, x, y}");
    const std::filesystem::path folder = file.parent_path();
    std::map<std::filesystem::path, ImageInfo> probed;
    size_t index = 0;
    for (const json& entry : root["images"]) {
      const std::string where = "images[" + std::to_string(index) + "] ";
      if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string() ||
          !entry.contains("x") || !entry.contains("y"))
        throw InputError(file, where + "is not an object with file, x and y");
      Placement placement;
      placement.file = folder / entry["file"].get<std::string>();
      placement.x = unsignedField(entry, "x", file, where);
      placement.y = unsignedField(entry, "y", file, where);
      const std::optional<uint32_t> width = placedSideField(entry, "width", file, where);
      const std::optional<uint32_t> height = placedSideField(entry, "height", file, where);
      const std::optional<int64_t> sourceX = sourceOffsetField(entry, "source_x", file, where);
      const std::optional<int64_t> sourceY = sourceOffsetField(entry, "source_y", file, where);
      placement.region = width || height || sourceX || sourceY;
      placement.sourceX = sourceX.value_or(0);
      placement.sourceY = sourceY.value_or(0);
      // Thousands of faces may name the same few images: each header is read once.
      const std::filesystem::path key = placement.file.lexically_normal();
      auto known = probed.find(key);
      if (known == probed.end())
        known = probed
                    .emplace(key, probe(placement.file,
                                        file.string() + " " + where.substr(0, where.size() - 1)))
                    .first;
      setImage(placement, known->second, width, height);
      layout.images.push_back(std::move(placement));
      ++index;
    }
    finish(layout, side, channels);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  } catch (const json::exception& e) {
    throw InputError(file, "unexpected value: " + jsonErrorText(e));
  }
  return layout;
}

Layout singleImageLayout(const std::filesystem::path& image, const LayoutOverrides& overrides) {
  Layout layout;
  layout.source = image;
  layout.description.pageSize = overrides.pageSize.value_or(128);
  layout.description.border = overrides.border.value_or(4);
  layout.description.colorSpace = overrides.colorSpace.value_or(ColorSpace::kSrgb);
  layout.filter = overrides.filter.value_or(MipFilter::kBox);
  layout.description.format = overrides.format.value_or(PixelFormat::kUnorm8);
  Placement placement;
  placement.file = image;
  setImage(placement, probeImageFile(image, "the command line"), std::nullopt, std::nullopt);
  layout.images.push_back(placement);
  finish(layout, overrides.side, overrides.channels);
  return layout;
}

MipFilter parseMipFilter(const std::string& name) {
  if (const auto filter = findByName(kMipFilterNames, name)) return *filter;
  throw std::invalid_argument("filter: '" + name + "' is not one of " +
                              joinedNames(kMipFilterNames));
}

PixelFormat parsePageFormat(const std::string& name) {
  if (const auto format = findByName(kPageFormatNames, name)) return *format;
  throw std::invalid_argument("format: '" + name + "' is not one of " +
                              joinedNames(kPageFormatNames));
}

ColorSpace parseColorSpace(const std::string& name) {
  if (const auto colorSpace = findByName(kColorSpaceNames, name)) return *colorSpace;
  throw std::invalid_argument("color_space: '" + name + "' is not one of " +
                              joinedNames(kColorSpaceNames));
}

std::string toString(MipFilter filter) { return std::string(nameOf(kMipFilterNames, filter)); }

}  // namespace vt
