#include "vt/oracle/render.h"

#include <utility>

#include "common/resource_limits.h"
#include "reference/api/api_internal.h"
#include "render/arithmetic_points.h"
#include "render/precision_model.h"
#include "render/precision_model_file.h"
#include "shader/needbuffer.h"

namespace vt::oracle {

namespace {

// The public names of the shipped models; the models themselves are render/precision_model.h's.
constexpr std::pair<Profile, const char*> kProfileNames[] = {{Profile::kExact, "exact"},
                                                             {Profile::kLlvmpipe, "llvmpipe"},
                                                             {Profile::kGl45, "gl45"},
                                                             {Profile::kSoftpipe, "softpipe"}};

}  // namespace

std::string toString(Profile profile) {
  for (const auto& [value, name] : kProfileNames)
    if (value == profile) return name;
  return "exact";
}

vt::PrecisionModel internalModel(Profile profile) { return vt::namedModel(toString(profile)); }

Profile parseProfile(const std::string& name) {
  for (const auto& [value, text] : kProfileNames)
    if (name == text) return value;
  throw Error("unknown precision model '" + name + "' (" + vt::kModelNames + ")");
}

Profile publicProfile(const vt::PrecisionModel& model) { return parseProfile(model.name); }

Profile profileForRenderer(const std::string& glRenderer) {
  return publicProfile(vt::modelForRenderer(glRenderer));
}

std::string toString(NeedEncoding encoding) {
  return encoding == NeedEncoding::k8Bit ? "need8" : "need32";
}
std::string toString(Filtering filtering) {
  return filtering == Filtering::kBilinear ? "bilinear" : "trilinear";
}
std::string toString(Sampling sampling) {
  return sampling == Sampling::kHardwareLinear ? "hardware_linear" : "texel_fetch";
}

vt::RenderSettings internalSettings(Viewport viewport, const RenderOptions& options) {
  vt::RenderSettings settings;
  settings.viewport = {viewport.width, viewport.height};
  vt::applyModel(settings, options.modelFile.empty() ? internalModel(options.profile)
                                                     : vt::readModelFile(options.modelFile));
  settings.trilinear = options.filtering == Filtering::kTrilinear;
  settings.exactFilter = options.sampling == Sampling::kTexelFetch;
  settings.need8 = options.needEncoding == NeedEncoding::k8Bit;
  settings.threads = options.threads;
  const uint64_t pixels = uint64_t(viewport.width) * uint64_t(viewport.height);
  if (!options.judgedColor.empty() || !options.judgedNeed.empty()) {
    if (options.judgedColor.size() != pixels * 4 || options.judgedNeed.size() != pixels * 4)
      throw Error("render: the judged frame has " + std::to_string(options.judgedColor.size() / 4) +
                  " colour and " + std::to_string(options.judgedNeed.size() / 4) +
                  " needbuffer pixels, the viewport " + std::to_string(pixels));
    settings.judged = {options.judgedColor, options.judgedNeed};
  }
  return settings;
}

ClipSpaceMesh internalMesh(const Scene& scene) {
  ClipSpaceMesh mesh;
  mesh.vertices.reserve(scene.vertices.size());
  for (const ClipVertex& v : scene.vertices)
    mesh.vertices.push_back({glm::vec4(v.x, v.y, v.z, v.w), glm::vec2(v.s, v.t)});
  if (!scene.indices.empty()) {
    if (scene.indices.size() % 3 != 0)
      throw Error("scene: " + std::to_string(scene.indices.size()) +
                  " indices are not a whole number of triangles");
    for (const uint32_t index : scene.indices)
      if (index >= scene.vertices.size())
        throw Error("scene: index " + std::to_string(index) + " names no vertex (there are " +
                    std::to_string(scene.vertices.size()) + ")");
    mesh.indices = scene.indices;
  } else {
    if (scene.vertices.size() % 3 != 0)
      throw Error("scene: " + std::to_string(scene.vertices.size()) +
                  " vertices without indices are not a whole number of triangles");
    for (uint32_t i = 0; i < scene.vertices.size(); ++i) mesh.indices.push_back(i);
  }
  return mesh;
}

vt::CacheState internalCache(const VirtualTextureReader& reader, const CacheState& cache) {
  std::vector<vt::PlacedPage> placed;
  placed.reserve(cache.pages.size());
  for (const ResidentPage& p : cache.pages) {
    const PageId page{p.x, p.y, p.level};
    if (!isValid(page))
      throw Error("cache state: page (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                  ") of level " + std::to_string(p.level) + " does not exist");
    placed.push_back({absoluteIndex(page), p.frameX, p.frameY});
  }
  return vt::placePages(reader, placed, cache.framesX, cache.framesY);
}

std::vector<uint32_t> flatNeed(std::span<const glm::uvec4> need) {
  std::vector<uint32_t> flat;
  flat.reserve(need.size() * 4);
  for (const glm::uvec4& v : need) flat.insert(flat.end(), {v.x, v.y, v.z, v.w});
  return flat;
}

Frame publicFrame(vt::Frame&& frame, const vt::RenderSettings& settings) {
  Frame result;
  result.needEncoding = settings.need8 ? NeedEncoding::k8Bit : NeedEncoding::k32Bit;
  result.model = settings.model ? settings.model->name : vt::arithmeticLabel(settings.arithmetic);
  const size_t pixels = frame.need.size();
  result.ambiguous.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) result.ambiguous[i] = vt::ambiguous(frame.sets, i) ? 1 : 0;
  result.judged = frame.sets.judged;
  if (!frame.sets.empty())
    result.sets = std::make_shared<const ResultSets>(ResultSets{std::move(frame.sets)});
  result.viewport = {frame.viewport.width, frame.viewport.height};
  result.color = std::move(frame.color);
  result.need = flatNeed(frame.need);
  result.depth = std::move(frame.depth);
  return result;
}

PreparedCache::PreparedCache(const Texture& texture, const CacheState& state)
    : impl_(translatingErrors([&] {
        auto impl = std::make_unique<Impl>(texture.impl(), std::nullopt);
        if (!state.allResident) impl->state = internalCache(texture.impl().reader, state);
        return impl;
      })) {}
PreparedCache::PreparedCache(PreparedCache&&) noexcept = default;
PreparedCache& PreparedCache::operator=(PreparedCache&&) noexcept = default;
PreparedCache::~PreparedCache() = default;

Frame render(const Texture& texture, const Scene& scene, const PreparedCache& cache,
             const RenderOptions& options) {
  return translatingErrors([&] {
    if (&cache.impl().texture != &texture.impl())
      throw Error("render: the cache state was prepared for another texture");
    const Viewport v = scene.viewport;
    if (v.width < 1 || v.height < 1 || uint64_t(v.width) > kMaxViewportSide ||
        uint64_t(v.height) > kMaxViewportSide)
      throw Error("scene: viewport " + std::to_string(v.width) + " x " + std::to_string(v.height) +
                  " is not within 1.." + std::to_string(kMaxViewportSide) + " per side");
    const VirtualTextureReader& reader = texture.impl().reader;
    if (options.needEncoding == NeedEncoding::k8Bit &&
        !need8Encodes(reader.description().finestLevel()))
      throw Error(reader.path().string() + ": the 8-bit needbuffer names pages of at most 12 " +
                  "levels below the root; the texture has " +
                  std::to_string(reader.description().finestLevel()));
    const ClipSpaceMesh mesh = internalMesh(scene);
    const vt::RenderSettings settings = internalSettings(v, options);
    if (!cache.impl().state)
      return publicFrame(reference::renderFrame(mesh, texture.impl().everything, settings),
                         settings);
    return publicFrame(reference::renderFrame(
                           mesh, cache.impl().stateFor(settings.arithmetic.blockDecoding), settings),
                       settings);
  });
}

Frame render(const Texture& texture, const Scene& scene, const CacheState& cache,
             const RenderOptions& options) {
  return render(texture, scene, PreparedCache(texture, cache), options);
}

}  // namespace vt::oracle
