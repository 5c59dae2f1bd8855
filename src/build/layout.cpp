#include "build/layout.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>

#include "common/error.h"

namespace vt {
namespace {

using nlohmann::json;

// Reads the image's header for its size and channels.
void probeImage(Placement& placement, const std::string& namedBy) {
  if (!std::filesystem::exists(placement.file))
    throw InputError(placement.file, "image not found (named by " + namedBy + ")");
  auto input = OIIO::ImageInput::open(placement.file.string());
  if (!input)
    throw InputError(placement.file,
                     "cannot read image (named by " + namedBy + "): " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw InputError(placement.file, "image has no texels");
  placement.width = static_cast<uint32_t>(spec.width);
  placement.height = static_cast<uint32_t>(spec.height);
  placement.channels = static_cast<uint32_t>(spec.nchannels);
}

uint64_t unsignedField(const json& object, const char* key, const std::filesystem::path& file,
                       const std::string& where) {
  const json& value = object.at(key);
  if (!value.is_number_unsigned())
    throw InputError(
        file, where + "field " + key + ": " + value.dump() + " is not a non-negative integer");
  return value.get<uint64_t>();
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
    extent = std::max({extent, image.x + image.width, image.y + image.height});
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

  for (const Placement& image : layout.images)
    if (image.x + image.width > textureSide || image.y + image.height > textureSide)
      throw InputError(file, "image " + image.file.string() + " (" + std::to_string(image.width) +
                                 " x " + std::to_string(image.height) + " at " +
                                 std::to_string(image.x) + ", " + std::to_string(image.y) +
                                 ") reaches outside the texture of " + std::to_string(textureSide) +
                                 " x " + std::to_string(textureSide) + " texels");

  // Overlaps: sweep the images in order of x; only those starting before one ends can overlap it.
  std::vector<size_t> order(layout.images.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return layout.images[a].x < layout.images[b].x; });
  for (size_t i = 0; i < order.size(); ++i) {
    const Placement& a = layout.images[order[i]];
    for (size_t j = i + 1; j < order.size(); ++j) {
      const Placement& b = layout.images[order[j]];
      if (b.x >= a.x + a.width) break;
      if (b.y < a.y + a.height && a.y < b.y + b.height)
        throw InputError(file,
                         "images " + a.file.string() + " and " + b.file.string() + " overlap");
    }
  }
}

}  // namespace

Layout readLayout(const std::filesystem::path& file, const LayoutOverrides& overrides) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "cannot open layout file");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::exception& e) {
    throw InputError(file, std::string("not valid JSON: ") + e.what());
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
      probeImage(placement, file.string() + " " + where.substr(0, where.size() - 1));
      layout.images.push_back(std::move(placement));
      ++index;
    }
    finish(layout, side, channels);
  } catch (const std::invalid_argument& e) {
    throw InputError(file, e.what());
  } catch (const json::exception& e) {
    throw InputError(file, std::string("unexpected value: ") + e.what());
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
  Placement placement;
  placement.file = image;
  probeImage(placement, "the command line");
  layout.images.push_back(placement);
  finish(layout, overrides.side, overrides.channels);
  return layout;
}

MipFilter parseMipFilter(const std::string& name) {
  if (name == "box") return MipFilter::kBox;
  if (name == "tent") return MipFilter::kTent;
  throw std::invalid_argument("filter: '" + name + "' is not one of box, tent");
}

ColorSpace parseColorSpace(const std::string& name) {
  if (name == "srgb") return ColorSpace::kSrgb;
  if (name == "linear") return ColorSpace::kLinear;
  throw std::invalid_argument("color_space: '" + name + "' is not one of srgb, linear");
}

std::string toString(MipFilter filter) { return filter == MipFilter::kBox ? "box" : "tent"; }

}  // namespace vt
