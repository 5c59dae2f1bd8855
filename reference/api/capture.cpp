#include "vt/oracle/capture.h"

#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "common/checksum.h"
#include "common/image_file.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "reference/api/api_internal.h"
#include "render/arithmetic_points.h"

static_assert(sizeof(vt::oracle::ClipVertex) == 24, "six float32 per vertex, as in the file");
static_assert(std::endian::native == std::endian::little,
              "capture data files are little-endian and read as they lie in memory");

namespace vt::oracle {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Stands for the resident pages while the manifest is dumped; they are written one per line.
constexpr const char* kPagesPlaceholder = "@resident pages@";

// A problem with one capture: "<manifest>: <problem>".
Error captureError(const fs::path& file, const std::string& problem) {
  return Error(file.string() + ": " + problem);
}

// Manifest fields: present, of their type, nothing unknown (an "extra" object is the engine's).
class Fields {
 public:
  Fields(const json& object, const fs::path& file, std::string where)
      : object_(object), file_(file), where_(std::move(where)) {
    if (!object_.is_object()) throw fail("is not a JSON object");
  }

  const json& at(const std::string& key, json::value_t type) {
    seen_.insert(key);
    const auto it = object_.find(key);
    if (it == object_.end()) throw fail("has no \"" + key + "\"");
    const bool number = type == json::value_t::number_unsigned;
    if (number ? !it->is_number_unsigned() : it->type() != type)
      throw fail("\"" + key + "\" is not " + (number ? "a whole number >= 0" : kindOf(type)));
    return *it;
  }
  bool has(const std::string& key) const { return object_.contains(key); }
  std::string text(const std::string& key) {
    return at(key, json::value_t::string).get<std::string>();
  }
  uint64_t count(const std::string& key, uint64_t limit) {
    const uint64_t value = at(key, json::value_t::number_unsigned).get<uint64_t>();
    if (value > limit)
      throw fail("\"" + key + "\" asks for " + std::to_string(value) + ", the limit is " +
                 std::to_string(limit));
    return value;
  }
  void noOthers() const {
    for (const auto& [key, value] : object_.items())
      if (!seen_.count(key) && key != "extra") throw fail("has an unknown field \"" + key + "\"");
  }
  Error fail(const std::string& problem) const {
    return captureError(file_, where_ + " " + problem);
  }

 private:
  static std::string kindOf(json::value_t type) {
    switch (type) {
      case json::value_t::string:
        return "a string";
      case json::value_t::object:
        return "an object";
      case json::value_t::array:
        return "an array";
      case json::value_t::boolean:
        return "true or false";
      default:
        return "of the expected type";
    }
  }
  const json& object_;
  const fs::path& file_;
  std::string where_;
  std::set<std::string> seen_;
};

template <class Enum>
Enum parseName(Fields& fields, const std::string& key,
               std::initializer_list<std::pair<const char*, Enum>> names) {
  const std::string name = fields.text(key);
  std::string known;
  for (const auto& [text, value] : names) {
    if (name == text) return value;
    known.append(known.empty() ? "" : ", ").append(text);
  }
  throw fields.fail("\"" + key + "\" is \"" + name + "\", not one of " + known);
}

// Data files lie in the manifest's folder or below it.
void requireRelativeName(const std::string& name, const fs::path& manifest) {
  const fs::path path(name);
  if (name.empty() || path.is_absolute() ||
      std::any_of(path.begin(), path.end(), [](const fs::path& part) { return part == ".."; }))
    throw captureError(manifest, "data file \"" + name +
                                     "\" must be named relative to the manifest's folder, "
                                     "without \"..\"");
}

// A data file named by the manifest, of exactly `bytes` bytes.
std::vector<std::byte> readDataFile(const fs::path& folder, const std::string& name, uint64_t bytes,
                                    const fs::path& manifest) {
  requireRelativeName(name, manifest);
  const fs::path file = folder / name;
  std::error_code error;
  const uint64_t size = fs::file_size(file, error);
  if (error) throw captureError(file, "cannot read data file: " + error.message());
  if (size != bytes)
    throw captureError(file, "holds " + std::to_string(size) + " bytes, the manifest asks for " +
                                 std::to_string(bytes));
  std::vector<std::byte> data(bytes);
  std::ifstream in(file, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(bytes)))
    throw captureError(file, "cannot read data file");
  return data;
}

// Rows top to bottom (files) <-> bottom to top (frames); either way.
template <class T>
std::vector<T> flipRows(std::span<const T> rows, size_t height) {
  std::vector<T> flipped(rows.size());
  const size_t stride = rows.size() / std::max<size_t>(1, height);
  for (size_t y = 0; y < height; ++y)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(y * stride), stride,
                flipped.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * stride));
  return flipped;
}

std::vector<uint8_t> readRgbaImage(const fs::path& folder, const std::string& name,
                                   Viewport viewport, const fs::path& manifest) {
  requireRelativeName(name, manifest);
  if (name.ends_with(".rgba8")) {
    // Raw: four bytes per pixel, rows top to bottom (written without an image library).
    const size_t pixels = static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
    const std::vector<std::byte> bytes = readDataFile(folder, name, pixels * 4, manifest);
    const auto* first = reinterpret_cast<const uint8_t*>(bytes.data());
    return flipRows<uint8_t>(std::span(first, bytes.size()), static_cast<size_t>(viewport.height));
  }
  const Image8 image = readImage8(folder / name, static_cast<int>(kMaxViewportSide));
  if (image.width != viewport.width || image.height != viewport.height || image.channels != 4)
    throw captureError(
        folder / name,
        "image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
            " with " + std::to_string(image.channels) + " channels, the viewport " +
            std::to_string(viewport.width) + " x " + std::to_string(viewport.height) + " RGBA");
  return flipRows<uint8_t>(image.texels, static_cast<size_t>(viewport.height));
}

uint64_t parseIdentity(Fields& fields, const std::string& key) {
  const std::string text = fields.text(key);
  uint64_t value = 0;
  if (text.size() != 16 ||
      !std::all_of(text.begin(), text.end(),
                   [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }) ||
      std::sscanf(text.c_str(), "%16" SCNx64, &value) != 1)
    throw fields.fail("\"" + key + "\" is \"" + text + "\", not 16 hexadecimal digits");
  return value;
}

// What the manifest says of itself: its format and version, the renderer, and the model that
// judges it (a file, relative to the manifest's folder, or a shipped pinned model's name).
void parseHeader(Fields& top, const fs::path& folder, Capture& capture) {
  if (top.text("format") != "vt-capture") throw top.fail("\"format\" is not \"vt-capture\"");
  const uint64_t version = top.count("version", 1000);
  if (version != kCaptureVersion)
    throw top.fail("has version " + std::to_string(version) + "; this oracle reads version " +
                   std::to_string(kCaptureVersion));
  capture.renderer = top.text("renderer");
  if (top.has("model")) {
    const fs::path model = top.text("model");
    if (model.empty()) throw top.fail("\"model\" is an empty file name");
    capture.model = model.is_absolute() ? model : folder / model;
  }
  if (top.has("fingerprint")) {
    capture.fingerprint = top.text("fingerprint");
    if (!vt::findArithmeticPoint(capture.fingerprint))
      throw top.fail("\"fingerprint\" is not a shipped pinned model (" +
                     vt::joinedArithmeticPointNames() + ")");
  }
}

void parseTexture(Fields& top, const fs::path& manifest, Capture& capture) {
  Fields texture(top.at("texture", json::value_t::object), manifest, "\"texture\"");
  const fs::path textureFile = texture.text("file");
  capture.texture = textureFile.is_absolute() ? textureFile : manifest.parent_path() / textureFile;
  capture.textureIdentity = parseIdentity(texture, "identity");
  texture.noOthers();
}

Viewport parseViewport(Fields& top, const fs::path& manifest) {
  Fields viewport(top.at("viewport", json::value_t::object), manifest, "\"viewport\"");
  const Viewport v = {static_cast<int>(viewport.count("width", kMaxViewportSide)),
                      static_cast<int>(viewport.count("height", kMaxViewportSide))};
  viewport.noOthers();
  if (v.width < 1 || v.height < 1) throw viewport.fail("has no pixels");
  return v;
}

// How the renderer encoded its needbuffer and sampled the cache.
void parseConventions(Fields& top, Capture& capture) {
  capture.needEncoding =
      parseName<NeedEncoding>(top, "needbuffer_encoding",
                              {{"need32", NeedEncoding::k32Bit}, {"need8", NeedEncoding::k8Bit}});
  capture.filtering = parseName<Filtering>(
      top, "filtering", {{"trilinear", Filtering::kTrilinear}, {"bilinear", Filtering::kBilinear}});
  capture.sampling = parseName<Sampling>(
      top, "sampling",
      {{"texel_fetch", Sampling::kTexelFetch}, {"hardware_linear", Sampling::kHardwareLinear}});
}

// Geometry: clip-space vertices and, optionally, indices.
void parseGeometry(Fields& top, const fs::path& manifest, Scene& scene) {
  const fs::path folder = manifest.parent_path();
  Fields geometry(top.at("geometry", json::value_t::object), manifest, "\"geometry\"");
  const uint64_t vertexCount = geometry.count("vertex_count", kMaxMapVertices);
  const std::vector<std::byte> vertices =
      readDataFile(folder, geometry.text("vertices"), vertexCount * sizeof(ClipVertex), manifest);
  scene.vertices.resize(vertexCount);
  std::memcpy(scene.vertices.data(), vertices.data(), vertices.size());
  if (geometry.has("indices")) {
    const uint64_t indexCount = geometry.count("index_count", kMaxMapIndices);
    const std::vector<std::byte> indices =
        readDataFile(folder, geometry.text("indices"), indexCount * 4, manifest);
    scene.indices.resize(indexCount);
    std::memcpy(scene.indices.data(), indices.data(), indices.size());
    if (indexCount % 3 != 0) throw geometry.fail("\"index_count\" is not a multiple of 3");
    for (const uint32_t index : scene.indices)
      if (index >= vertexCount)
        throw geometry.fail("index " + std::to_string(index) + " names no vertex (there are " +
                            std::to_string(vertexCount) + ")");
  } else if (vertexCount % 3 != 0) {
    throw geometry.fail("\"vertex_count\" without indices is not a multiple of 3");
  }
  geometry.noOthers();
}

// One resident page, [level, px, py, frame_x, frame_y].
ResidentPage parseResidentPage(const Fields& cache, const json& page) {
  if (!page.is_array() || page.size() != 5 ||
      !std::all_of(page.begin(), page.end(), [](const json& n) { return n.is_number_unsigned(); }))
    throw cache.fail("page " + page.dump() + " is not [level, px, py, frame_x, frame_y]");
  const auto number = [&](size_t k) {
    const uint64_t n = page[k].get<uint64_t>();
    if (n > UINT32_MAX) throw cache.fail("page " + page.dump() + " has a number above 2^32");
    return static_cast<uint32_t>(n);
  };
  return {number(0), number(1), number(2), number(3), number(4)};
}

// The cache state: every page resident, or the cache's frames and the pages they hold.
void parseCache(Fields& top, const fs::path& manifest, CacheState& state) {
  Fields cache(top.at("cache", json::value_t::object), manifest, "\"cache\"");
  state.allResident = cache.at("all_resident", json::value_t::boolean).get<bool>();
  if (!state.allResident) {
    state.framesX = static_cast<uint32_t>(cache.count("frames_x", kMaxCacheSideTexels));
    state.framesY = static_cast<uint32_t>(cache.count("frames_y", kMaxCacheSideTexels));
    if (state.framesX == 0 || state.framesY == 0) throw cache.fail("has no frames");
    const json& pages = cache.at("pages", json::value_t::array);
    if (pages.size() > uint64_t{state.framesX} * state.framesY)
      throw cache.fail("lists " + std::to_string(pages.size()) + " pages for " +
                       std::to_string(uint64_t{state.framesX} * state.framesY) + " frames");
    for (const json& page : pages) state.pages.push_back(parseResidentPage(cache, page));
  } else if (cache.has("pages")) {
    throw cache.fail("lists pages but says all pages are resident");
  }
  cache.noOthers();
}

// The frame: colour and needbuffer.
void readFrame(Fields& top, const fs::path& manifest, Capture& capture) {
  const fs::path folder = manifest.parent_path();
  const Viewport v = capture.scene.viewport;
  const auto pixels = static_cast<uint64_t>(v.width) * static_cast<uint64_t>(v.height);
  capture.color = readRgbaImage(folder, top.text("color"), v, manifest);
  const std::string needFile = top.text("needbuffer");
  if (capture.needEncoding == NeedEncoding::k8Bit) {
    const std::vector<uint8_t> need = readRgbaImage(folder, needFile, v, manifest);
    capture.need.assign(need.begin(), need.end());
  } else {
    const std::vector<std::byte> bytes = readDataFile(folder, needFile, pixels * 16, manifest);
    std::vector<uint32_t> rows(pixels * 4);
    std::memcpy(rows.data(), bytes.data(), bytes.size());
    capture.need = flipRows<uint32_t>(rows, static_cast<size_t>(v.height));
  }
}

// The manifest's fields in the order they are checked, so the first problem is the one named.
Capture parseManifest(const json& root, const fs::path& manifest) {
  Capture capture;
  Fields top(root, manifest, "manifest");
  parseHeader(top, manifest.parent_path(), capture);
  parseTexture(top, manifest, capture);
  capture.scene.viewport = parseViewport(top, manifest);
  parseConventions(top, capture);
  parseGeometry(top, manifest, capture.scene);
  parseCache(top, manifest, capture.cache);
  readFrame(top, manifest, capture);
  top.noOthers();
  return capture;
}

// `file` named from `folder` (the manifest's), or absolute where no relative name reaches it.
fs::path relativeTo(const fs::path& folder, const fs::path& file) {
  const fs::path absolute = fs::absolute(file).lexically_normal();
  const fs::path relative = absolute.lexically_relative(fs::absolute(folder).lexically_normal());
  return relative.empty() ? absolute : relative;
}

void writeData(const fs::path& file, std::span<const std::byte> bytes) {
  writeFileAtomically(file, bytes);
}

}  // namespace

Capture readCapture(const fs::path& manifest) {
  return translatingErrors([&] {
    try {
      return parseManifest(readJsonFile(manifest, "capture manifest"), manifest);
    } catch (const json::exception& e) {
      throw captureError(manifest, e.what());
    }
  });
}

void writeCapture(const fs::path& manifest, const Capture& capture) {
  translatingErrors([&] {
    const Viewport v = capture.scene.viewport;
    const auto pixels = static_cast<size_t>(v.width) * static_cast<size_t>(v.height);
    if (v.width < 1 || v.height < 1 || capture.color.size() != pixels * 4 ||
        capture.need.size() != pixels * 4)
      throw captureError(manifest, "capture's images do not match its viewport");
    const fs::path folder = manifest.parent_path();
    const std::string stem = manifest.stem().string();
    nlohmann::ordered_json root;  // fields in the order the guide lists them
    root["format"] = "vt-capture";
    root["version"] = kCaptureVersion;
    root["renderer"] = capture.renderer;
    if (!capture.model.empty()) root["model"] = relativeTo(folder, capture.model).string();
    if (!capture.fingerprint.empty()) root["fingerprint"] = capture.fingerprint;
    root["texture"] = {{"file", relativeTo(folder, capture.texture).string()},
                       {"identity", checksumText(capture.textureIdentity)}};
    root["viewport"] = {{"width", v.width}, {"height", v.height}};
    root["needbuffer_encoding"] = toString(capture.needEncoding);
    root["filtering"] = toString(capture.filtering);
    root["sampling"] = toString(capture.sampling);

    nlohmann::ordered_json geometry = {{"vertices", stem + ".vertices.f32"},
                                       {"vertex_count", capture.scene.vertices.size()}};
    writeData(folder / (stem + ".vertices.f32"), std::as_bytes(std::span(capture.scene.vertices)));
    if (!capture.scene.indices.empty()) {
      geometry["indices"] = stem + ".indices.u32";
      geometry["index_count"] = capture.scene.indices.size();
      writeData(folder / (stem + ".indices.u32"), std::as_bytes(std::span(capture.scene.indices)));
    }
    root["geometry"] = geometry;

    nlohmann::ordered_json cache = {{"all_resident", capture.cache.allResident}};
    if (!capture.cache.allResident) {
      cache["frames_x"] = capture.cache.framesX;
      cache["frames_y"] = capture.cache.framesY;
      cache["pages"] = kPagesPlaceholder;
    }
    root["cache"] = cache;

    const auto height = static_cast<size_t>(v.height);
    root["color"] = stem + ".color.png";
    const std::vector<uint8_t> color = flipRows<uint8_t>(capture.color, height);
    writeImage8(folder / (stem + ".color.png"), static_cast<uint32_t>(v.width),
                static_cast<uint32_t>(v.height), 4, std::as_bytes(std::span(color)));
    const std::vector<uint32_t> need = flipRows<uint32_t>(capture.need, height);
    if (capture.needEncoding == NeedEncoding::k8Bit) {
      std::vector<uint8_t> bytes(need.size());
      for (size_t i = 0; i < need.size(); ++i) {
        if (need[i] > 255) throw captureError(manifest, "8-bit needbuffer value above 255");
        bytes[i] = static_cast<uint8_t>(need[i]);
      }
      root["needbuffer"] = stem + ".need.png";
      writeImage8(folder / (stem + ".need.png"), static_cast<uint32_t>(v.width),
                  static_cast<uint32_t>(v.height), 4, std::as_bytes(std::span(bytes)));
    } else {
      root["needbuffer"] = stem + ".need.u32";
      writeData(folder / (stem + ".need.u32"), std::as_bytes(std::span(need)));
    }
    // The manifest last: it names only files that are complete. One resident page per line.
    std::string text = root.dump(2);
    if (!capture.cache.allResident) {
      std::string pages = "[";
      for (const ResidentPage& p : capture.cache.pages)
        pages.append(pages.size() > 1 ? ",\n      [" : "\n      [")
            .append(std::to_string(p.level) + ", " + std::to_string(p.x) + ", " +
                    std::to_string(p.y) + ", " + std::to_string(p.frameX) + ", " +
                    std::to_string(p.frameY) + "]");
      pages.append("\n    ]");
      text.replace(text.find(json(kPagesPlaceholder).dump()), json(kPagesPlaceholder).dump().size(),
                   pages);
    }
    writeFileAtomically(manifest, text + "\n");
  });
}

std::vector<fs::path> findCaptures(const fs::path& folder) {
  return translatingErrors([&] {
    std::error_code error;
    std::vector<fs::path> manifests;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
      if (entry.path().extension() == ".json" && entry.is_regular_file())
        manifests.push_back(entry.path());
    if (error) throw captureError(folder, "cannot list the captures: " + error.message());
    std::sort(manifests.begin(), manifests.end());
    return manifests;
  });
}

RenderOptions renderOptions(const Capture& capture, Profile profile) {
  RenderOptions options;
  options.profile = profile;
  options.needEncoding = capture.needEncoding;
  options.filtering = capture.filtering;
  options.sampling = capture.sampling;
  return options;
}

namespace {

CaptureCheck checkWith(const Capture& capture, const Texture& texture, RenderOptions options,
                       SetScope scope) {
  if (texture.identity() != capture.textureIdentity)
    throw Error(texture.path().string() + ": texture identity " + checksumText(texture.identity()) +
                " does not match the capture's " + checksumText(capture.textureIdentity) +
                " (the frame was drawn from another texture)");
  CaptureCheck check;
  if (scope == SetScope::kDiffering) {
    options.judgedColor = capture.color;
    options.judgedNeed = capture.need;
  }
  check.oracle = render(texture, capture.scene, capture.cache, options);
  check.comparison = compare(check.oracle, capture.color, capture.need);
  return check;
}

}  // namespace

CaptureCheck checkCapture(const Capture& capture, const Texture& texture, Profile profile,
                          unsigned threads, SetScope scope) {
  RenderOptions options = renderOptions(capture, profile);
  options.threads = threads;
  return checkWith(capture, texture, options, scope);
}

CaptureCheck checkCapture(const Capture& capture, const Texture& texture,
                          const std::filesystem::path& modelFile, unsigned threads,
                          SetScope scope) {
  RenderOptions options = renderOptions(capture, Profile::kExact);
  options.modelFile = modelFile.string();
  options.threads = threads;
  return checkWith(capture, texture, options, scope);
}

}  // namespace vt::oracle
