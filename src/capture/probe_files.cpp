#include "capture/probe_files.h"

#include <array>
#include <bit>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <span>

#include "common/error.h"
#include "common/input_file.h"
#include "common/json_text.h"
#include "common/posix_file.h"
#include "common/resource_limits.h"
#include "format/block_decoding.h"

namespace vt::capture {
namespace {

static_assert(std::endian::native == std::endian::little, "probe files are little-endian");

// Limits of what a request may ask for: the calibration's largest probe is 65,536 inputs and
// 420 triangles at 480 x 320; these leave room for bigger ones and refuse absurd claims.
constexpr size_t kMaxInputs = size_t{1} << 22;
constexpr int kMaxSide = 4096;
constexpr size_t kMaxVertices = size_t{1} << 20;
constexpr size_t kMaxBodyBytes = size_t{1} << 20;
// A probe's texture: a side as long as a cache texture's (GL_LINEAR at the cache's sizes:
// calibrate/filter_fit.h), at most 2^22 texels (16 MiB of RGBA8).
constexpr int kMaxTextureSide = static_cast<int>(kMaxCacheSideTexels);
constexpr size_t kMaxTexels = size_t{1} << 22;

std::string stem(size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "probe-%04zu", index);
  return name;
}

const char* kindName(ProbeRequest::Kind kind) {
  switch (kind) {
    case ProbeRequest::Kind::kShader:
      return "shader";
    case ProbeRequest::Kind::kColour:
      return "colour";
    case ProbeRequest::Kind::kTriangles:
      return "triangles";
  }
  return "";
}

template <typename T>
void writeArray(const std::filesystem::path& file, const std::vector<T>& values) {
  writeFileAtomically(file, std::as_bytes(std::span(values)));
}

// `count` values of T from `file`, which must hold exactly that many.
template <typename T>
std::vector<T> readArray(const std::filesystem::path& file, size_t count, const std::string& what) {
  const std::string bytes = readTextFile(file, what, count * sizeof(T));
  if (bytes.size() != count * sizeof(T))
    throw InputError(file, what + ": " + std::to_string(bytes.size()) + " bytes, expected " +
                               std::to_string(count * sizeof(T)));
  std::vector<T> values(count);
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

// A whole number from lo to hi. A fraction, a negative number or a float (1e30 would not convert
// to an integer: undefined behaviour) is refused with the field named.
size_t wholeNumber(const nlohmann::json& value, const std::string& field, size_t lo, size_t hi,
                   const std::filesystem::path& file) {
  if (!value.is_number_unsigned())
    throw InputError(file, "field " + field + " is not a whole number from " + std::to_string(lo) +
                               " to " + std::to_string(hi));
  const uint64_t v = value.get<uint64_t>();
  if (v < lo || v > hi)
    throw InputError(file, "field " + field + ": " + std::to_string(v) + " is not from " +
                               std::to_string(lo) + " to " + std::to_string(hi));
  return static_cast<size_t>(v);
}

size_t sizeField(const nlohmann::json& j, const char* key, size_t lo, size_t hi,
                 const std::filesystem::path& file) {
  return wholeNumber(j.at(key), key, lo, hi, file);
}

// A [width, height] field ("viewport", "texture_size"), each from lo to hi.
std::array<size_t, 2> sideField(const nlohmann::json& j, const char* key, size_t lo, size_t hi,
                                const std::filesystem::path& file) {
  const nlohmann::json& pair = j.at(key);
  if (!pair.is_array() || pair.size() != 2)
    throw InputError(file, std::string("field ") + key + " is not [width, height]");
  return {wholeNumber(pair[0], std::string(key) + "[0]", lo, hi, file),
          wholeNumber(pair[1], std::string(key) + "[1]", lo, hi, file)};
}

// The texture's size, refused where a side or the texel count is beyond the limits above.
std::array<size_t, 2> textureSize(const nlohmann::json& j, int smallest,
                                  const std::filesystem::path& file) {
  const auto [w, h] = sideField(j, "texture_size", smallest, kMaxTextureSide, file);
  if (w * h > kMaxTexels)
    throw InputError(file, "texture_size " + std::to_string(w) + " x " + std::to_string(h) +
                               " is more than 4,194,304 texels");
  return {w, h};
}

struct RasterPixel {
  int32_t triangle;
  float s, t, dsdx, dtdx, dsdy, dtdy, depth;
};

}  // namespace

bool sameRequest(const ProbeRequest& a, const ProbeRequest& b) {
  if (a.kind != b.kind) return false;
  if (a.kind == ProbeRequest::Kind::kTriangles) {
    if (a.viewport.width != b.viewport.width || a.viewport.height != b.viewport.height ||
        a.depth != b.depth || a.interpolation != b.interpolation ||
        a.mesh.indices != b.mesh.indices ||
        a.mesh.vertices.size() != b.mesh.vertices.size())
      return false;
    return std::memcmp(a.mesh.vertices.data(), b.mesh.vertices.data(),
                       a.mesh.vertices.size() * sizeof(ClipVertex)) == 0;
  }
  const calibrate::ShaderProbe &p = a.shader, &q = b.shader;
  return p.body == q.body && p.width == q.width && p.textureSize == q.textureSize &&
         p.linear == q.linear && p.clipped == q.clipped && p.texels == q.texels &&
         p.blockFormat == q.blockFormat && p.blocks == q.blocks &&
         p.inputs.size() == q.inputs.size() &&
         std::memcmp(p.inputs.data(), q.inputs.data(), p.inputs.size() * sizeof(glm::vec4)) == 0;
}

void writeProbeRequest(const std::filesystem::path& folder, size_t index,
                       const ProbeRequest& request) {
  const std::string name = stem(index);
  nlohmann::ordered_json j = {
      {"format", "vt-probe"}, {"version", 1}, {"kind", kindName(request.kind)}};
  if (request.kind == ProbeRequest::Kind::kTriangles) {
    std::vector<float> vertices;
    for (const ClipVertex& v : request.mesh.vertices)
      vertices.insert(vertices.end(),
                      {v.position.x, v.position.y, v.position.z, v.position.w, v.uv.x, v.uv.y});
    writeArray(folder / (name + ".vertices.f32"), vertices);
    writeArray(folder / (name + ".indices.u32"), request.mesh.indices);
    j["vertices"] = name + ".vertices.f32";
    j["vertex_count"] = request.mesh.vertices.size();
    j["indices"] = name + ".indices.u32";
    j["index_count"] = request.mesh.indices.size();
    j["viewport"] = {request.viewport.width, request.viewport.height};
    j["depth"] = request.depth == DepthFormat::kDepth24 ? "depth24" : "depth32f";
    // Written only where not the default, so that the first pack's requests read as before.
    if (request.interpolation == calibrate::Interpolation::kNoPerspective)
      j["interpolation"] = "noperspective";
  } else {
    const calibrate::ShaderProbe& p = request.shader;
    writeArray(folder / (name + ".inputs.f32"), p.inputs);
    j["body"] = p.body;
    j["width"] = p.width;
    j["inputs"] = name + ".inputs.f32";
    j["input_count"] = p.inputs.size();
    if (!p.texels.empty()) {
      writeArray(folder / (name + ".texels.rgba8"), p.texels);
      j["texels"] = name + ".texels.rgba8";
      j["texture_size"] = {p.textureSize.x, p.textureSize.y};
    }
    if (!p.blocks.empty()) {
      const std::string format = toString(p.blockFormat);
      writeArray(folder / (name + ".blocks." + format), p.blocks);
      j["blocks"] = name + ".blocks." + format;
      j["block_format"] = format;
      j["texture_size"] = {p.textureSize.x, p.textureSize.y};
    }
    j["linear"] = p.linear;
    j["clipped"] = p.clipped;
  }
  writeFileAtomically(folder / (name + ".json"), j.dump(1) + "\n");
}

ProbeRequest readProbeRequest(const std::filesystem::path& folder, size_t index) {
  const std::filesystem::path file = folder / (stem(index) + ".json");
  ProbeRequest r;
  try {
    const nlohmann::json j = readJsonFile(file, "probe request");
    if (j.at("format") != "vt-probe" || j.at("version") != 1)
      throw InputError(file, "not a vt-probe request of version 1");
    const std::string kind = j.at("kind").get<std::string>();
    // Data files are named by the request's index, never by a path the file gives.
    const std::string name = stem(index);
    if (kind == "triangles") {
      r.kind = ProbeRequest::Kind::kTriangles;
      const size_t vertexCount = sizeField(j, "vertex_count", 0, kMaxVertices, file);
      const size_t indexCount = sizeField(j, "index_count", 0, 3 * kMaxVertices, file);
      if (indexCount % 3) throw InputError(file, "index_count is not a multiple of 3");
      const auto [width, height] = sideField(j, "viewport", 1, kMaxSide, file);
      r.viewport = {static_cast<int>(width), static_cast<int>(height)};
      const std::string depth = j.at("depth").get<std::string>();
      if (depth != "depth24" && depth != "depth32f")
        throw InputError(file, "depth '" + depth + "' is not depth24 or depth32f");
      r.depth = depth == "depth24" ? DepthFormat::kDepth24 : DepthFormat::kDepth32F;
      if (j.contains("interpolation")) {
        if (j.at("interpolation") != "noperspective")
          throw InputError(file, "interpolation is not noperspective (perspective is the default "
                                 "and is not named)");
        r.interpolation = calibrate::Interpolation::kNoPerspective;
      }
      const std::vector<float> v =
          readArray<float>(folder / (name + ".vertices.f32"), vertexCount * 6, "vertices");
      for (size_t k = 0; k < vertexCount; ++k)
        r.mesh.vertices.push_back(
            {{v[6 * k], v[6 * k + 1], v[6 * k + 2], v[6 * k + 3]}, {v[6 * k + 4], v[6 * k + 5]}});
      r.mesh.indices = readArray<uint32_t>(folder / (name + ".indices.u32"), indexCount, "indices");
      for (uint32_t i : r.mesh.indices)
        if (i >= vertexCount) throw InputError(file, "an index names no vertex");
      return r;
    }
    if (kind != "shader" && kind != "colour")
      throw InputError(file, "kind '" + kind + "' is not shader, colour or triangles");
    r.kind = kind == "shader" ? ProbeRequest::Kind::kShader : ProbeRequest::Kind::kColour;
    calibrate::ShaderProbe& p = r.shader;
    p.body = j.at("body").get<std::string>();
    if (p.body.size() > kMaxBodyBytes) throw InputError(file, "body is longer than 1 MiB");
    const size_t count = sizeField(j, "input_count", 1, kMaxInputs, file);
    p.width = static_cast<int>(sizeField(j, "width", 1, kMaxSide, file));
    if (count % static_cast<size_t>(p.width) || count / static_cast<size_t>(p.width) > kMaxSide)
      throw InputError(file, "input_count is not a whole number of rows of at most 4096");
    p.inputs = readArray<glm::vec4>(folder / (name + ".inputs.f32"), count, "inputs");
    p.linear = j.at("linear").get<bool>();
    p.clipped = j.at("clipped").get<bool>();
    if (j.contains("texels")) {
      const auto [w, h] = textureSize(j, 1, file);
      p.textureSize = {static_cast<int>(w), static_cast<int>(h)};
      p.texels = readArray<glm::u8vec4>(folder / (name + ".texels.rgba8"), w * h, "texels");
    }
    if (j.contains("blocks")) {
      if (j.contains("texels")) throw InputError(file, "has both texels and blocks");
      const std::string format = j.at("block_format").get<std::string>();
      if (format != "bc1" && format != "bc3")
        throw InputError(file, "block_format '" + format + "' is not bc1 or bc3");
      p.blockFormat = format == "bc1" ? PixelFormat::kBc1 : PixelFormat::kBc3;
      const auto [w, h] = textureSize(j, 4, file);
      if (w % 4 || h % 4) throw InputError(file, "texture_size is not whole blocks of 4 x 4");
      p.textureSize = {static_cast<int>(w), static_cast<int>(h)};
      p.blocks = readArray<std::byte>(folder / (name + ".blocks." + format),
                                      (w / 4) * (h / 4) * blockBytes(p.blockFormat), "blocks");
    }
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, jsonErrorText(e));
  }
}

void writeProbeResult(const std::filesystem::path& folder, size_t index,
                      const ProbeRequest& request, const ProbeResult& result) {
  const std::filesystem::path file = folder / (stem(index) + ".result");
  switch (request.kind) {
    case ProbeRequest::Kind::kShader:
      writeArray(file, result.values);
      return;
    case ProbeRequest::Kind::kColour:
      writeArray(file, result.bytes);
      return;
    case ProbeRequest::Kind::kTriangles: {
      const calibrate::RasterReadback& r = result.raster;
      std::vector<RasterPixel> pixels(r.triangle.size());
      for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = {r.triangle[i],      r.uv[i].x,          r.uv[i].y,          r.derivatives[i].x,
                     r.derivatives[i].y, r.derivatives[i].z, r.derivatives[i].w, r.depth[i]};
      writeArray(file, pixels);
      return;
    }
  }
}

ProbeResult readProbeResult(const std::filesystem::path& folder, size_t index,
                            const ProbeRequest& request) {
  const std::filesystem::path file = folder / (stem(index) + ".result");
  ProbeResult result;
  switch (request.kind) {
    case ProbeRequest::Kind::kShader:
      result.values = readArray<glm::vec4>(file, request.shader.inputs.size(), "probe result");
      break;
    case ProbeRequest::Kind::kColour:
      result.bytes = readArray<glm::u8vec4>(file, request.shader.inputs.size(), "probe result");
      break;
    case ProbeRequest::Kind::kTriangles: {
      const size_t n = static_cast<size_t>(request.viewport.width) *
                       static_cast<size_t>(request.viewport.height);
      const std::vector<RasterPixel> pixels = readArray<RasterPixel>(file, n, "probe result");
      calibrate::RasterReadback& r = result.raster;
      const auto triangles = static_cast<int64_t>(request.mesh.indices.size() / 3);
      for (const RasterPixel& p : pixels) {
        if (p.triangle < -1 || p.triangle >= triangles)
          throw InputError(file, "a pixel names no triangle of the request");
        r.triangle.push_back(p.triangle);
        r.uv.push_back({p.s, p.t});
        r.derivatives.push_back({p.dsdx, p.dtdx, p.dsdy, p.dtdy});
        r.depth.push_back(p.depth);
      }
      break;
    }
  }
  return result;
}

void writeProbeFolder(const std::filesystem::path& folder, const ProbeFolder& description) {
  const nlohmann::ordered_json j = {{"format", "vt-probes"},
                                    {"version", 1},
                                    {"count", description.count},
                                    {"renderer", description.identity.renderer},
                                    {"version_string", description.identity.version},
                                    {"vendor", description.identity.vendor}};
  writeFileAtomically(folder / "probes.json", j.dump(1) + "\n");
}

ProbeFolder readProbeFolder(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "probes.json";
  try {
    const nlohmann::json j = readJsonFile(file, "probe folder description");
    if (j.at("format") != "vt-probes" || j.at("version") != 1)
      throw InputError(file, "not a vt-probes description of version 1");
    ProbeFolder d;
    d.count = sizeField(j, "count", 1, 100000, file);
    d.identity = {j.at("renderer").get<std::string>(), j.at("version_string").get<std::string>(),
                  j.at("vendor").get<std::string>()};
    return d;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, jsonErrorText(e));
  }
}

size_t countProbeRequests(const std::filesystem::path& folder) {
  size_t count = 0;
  while (count < 100000 && std::filesystem::is_regular_file(folder / (stem(count) + ".json")))
    ++count;
  return count;
}

ProbeResult drawHere(const ProbeRequest& request) {
  ProbeResult result;
  switch (request.kind) {
    case ProbeRequest::Kind::kShader:
      result.values = calibrate::drawShaderProbeHere(request.shader);
      break;
    case ProbeRequest::Kind::kColour:
      result.bytes = calibrate::drawColourProbeHere(request.shader);
      break;
    case ProbeRequest::Kind::kTriangles:
      result.raster = calibrate::drawTrianglesHere(request.mesh, request.viewport, request.depth,
                                                   request.interpolation);
      break;
  }
  return result;
}

}  // namespace vt::capture
