#include "calibrate/filter_fit.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <random>
#include <span>

#include "common/random_draws.h"
#include "format/block_decoding.h"
#include "probes/probe_draws.h"
#include "reference/linear_filter.h"

namespace vt::calibrate {
namespace {

// A GL_LINEAR probe of a `size` texture (its texels or blocks left to the caller) sampled with
// textureLod at `coordinates`.
ShaderProbe linearProbe(glm::ivec2 size, const std::vector<glm::vec2>& coordinates) {
  ShaderProbe probe;
  probe.body = "result = textureLod(uTexture, x.xy, 0.0);";
  probe.textureSize = size;
  probe.linear = true;
  for (const glm::vec2 u : coordinates) probe.inputs.push_back(glm::vec4(u, 0.0f, 0.0f));
  return probe;
}

// A texture of random texels (a fixed seed) sampled with textureLod at `coordinates`.
FilterSample sample(int width, int height, const std::vector<glm::vec2>& coordinates,
                    std::mt19937& random) {
  FilterSample s{linearProbe({width, height}, coordinates), {}};
  for (int i = 0; i < width * height; ++i) {
    const uint32_t bits = static_cast<uint32_t>(random());
    s.probe.texels.push_back(
        glm::u8vec4(bits & 255, (bits >> 8) & 255, (bits >> 16) & 255, bits >> 24));
  }
  s.out = runShaderProbe(s.probe);
  return s;
}

// `count` normalized coordinates along a `side` texture: texel positions on a 2^-12 grid or,
// every other one, on and one float beside 1/256-texel steps (exactly where `side` is a power of
// two, else the nearest float).
std::vector<float> stepPositions(int side, int count, std::mt19937& random) {
  std::vector<float> positions;
  for (int i = 0; i < count; ++i) {
    const uint32_t r = static_cast<uint32_t>(random());
    float v = static_cast<float>(r % (static_cast<uint32_t>(side) * 4096)) / 4096.0f;
    if (i % 2 == 1) {
      v = static_cast<float>(r % (static_cast<uint32_t>(side) * 256)) / 256.0f;
      if (r & (1u << 30)) v = std::nextafter(v, (r & (1u << 31)) ? 0.0f : 1e6f);
    }
    positions.push_back(v / static_cast<float>(side));
  }
  return positions;
}

}  // namespace

std::vector<FilterSample> drawFilterProbes() {
  std::mt19937 random(7);
  std::vector<FilterSample> result;
  constexpr int kSide = 16;
  std::vector<glm::vec2> steps;
  for (int i = 0; i < 32768; ++i) {
    glm::vec2 t;
    for (int k = 0; k < 2; ++k) {
      const uint32_t r = static_cast<uint32_t>(random());
      float v = static_cast<float>(r % (kSide * 4096)) / 4096.0f;
      if (i % 2 == 1) {
        v = static_cast<float>(r % (kSide * 256)) / 256.0f;
        if (r & (1u << 30)) v = std::nextafter(v, (r & (1u << 31)) ? 0.0f : 100.0f);
      }
      t[k] = v / static_cast<float>(kSide);  // exact: a power of two
    }
    steps.push_back(t);
  }
  std::vector<glm::vec2> uniform;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 16384; ++i) uniform.push_back(drawPoint([&] { return unit(random); }));
  result.push_back(sample(kSide, kSide, steps, random));
  result.push_back(sample(24, 40, uniform, random));
  return result;
}

namespace {

// 4,096 random coordinates of full float precision and 4,096 on and beside 1/256-texel steps along
// the texture's long side (the short side at random).
std::vector<glm::vec2> cacheCoordinates(glm::ivec2 size, std::mt19937& random) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::vec2> coordinates;
  for (int i = 0; i < 4096; ++i) coordinates.push_back(drawPoint([&] { return unit(random); }));
  const int along = size.x > size.y ? 0 : 1;
  for (const float u : stepPositions(size[along], 4096, random)) {
    glm::vec2 t(unit(random));
    t[along] = u;
    coordinates.push_back(t);
  }
  return coordinates;
}

// A texture of random blocks of `format` sampled with textureLod at `coordinates`; its texels
// decoded with `decoding` (the fit reads texels), or none where `decoding` is not exact.
FilterSample sampleBlocks(PixelFormat format, glm::ivec2 size,
                          const std::vector<glm::vec2>& coordinates,
                          const std::optional<BlockDecoding>& decoding, std::mt19937& random) {
  FilterSample s{linearProbe(size, coordinates), {}};
  s.probe.blockFormat = format;
  s.probe.blocks.resize(static_cast<size_t>(size.x / 4 * (size.y / 4)) * blockBytes(format));
  for (std::byte& b : s.probe.blocks) b = static_cast<std::byte>(random() & 0xff);
  s.out = runShaderProbe(s.probe);
  if (!decoding) return s;
  s.probe.texels.resize(static_cast<size_t>(size.x * size.y));
  decodeBlocks(format, static_cast<uint32_t>(size.x), static_cast<uint32_t>(size.y), s.probe.blocks,
               std::as_writable_bytes(std::span(s.probe.texels)), *decoding);
  return s;
}

}  // namespace

bool drawFilterProbesAtCacheSizes(std::vector<FilterSample>& samples,
                                  const CacheDecoding& decoding) {
  const glm::ivec2 sizes[] = {{16384, 2}, {2, 16384}, {4080, 4}};
  const PixelFormat blockFormats[] = {PixelFormat::kBc1, PixelFormat::kBc3};
  if (!holdsOptionalGroup(std::size(sizes) + std::size(blockFormats))) return false;
  std::mt19937 random(16384);
  for (const glm::ivec2 size : sizes)
    samples.push_back(sample(size.x, size.y, cacheCoordinates(size, random), random));
  // The GL renderer's compressed cache: 4096 texels wide (a power of two, so that coordinates on
  // steps are exact).
  const glm::ivec2 blockSize{4096, 8};
  for (const PixelFormat format : blockFormats) {
    const bool exact = format == PixelFormat::kBc1 ? decoding.colourPinned
                                                   : decoding.colourPinned && decoding.alphaPinned;
    FilterSample s = sampleBlocks(format, blockSize, cacheCoordinates(blockSize, random),
                                  exact ? std::optional(decoding.decoding) : std::nullopt, random);
    if (exact) samples.push_back(std::move(s));
  }
  return true;
}

bool reproducesSample(const ShaderProbe& probe, size_t i, const glm::vec4& got,
                      const Filter& filter, UnormConversion conversion) {
  const auto fetch8 = [&](glm::ivec2 t) {
    return probe.texels[static_cast<size_t>(t.y * probe.textureSize.x + t.x)];
  };
  const glm::vec4 expected = reference::sampleLinearAt(fetch8, glm::vec2(probe.inputs[i]),
                                                       probe.textureSize, filter, conversion);
  const bool wholeUnits = filter.weights == FilterWeights::kFixedPoint8 ||
                          (filter.weights == FilterWeights::kFixedPointCorners &&
                           filter.output == FilterOutput::kUnorm8);
  for (int c = 0; c < 4; ++c) {
    if (wholeUnits) {
      // A whole number of 1/255: how it becomes a float (k / 255 or k * (1 / 255)) does not reach
      // an RGBA8 target.
      const float units = got[c] * 255.0f;
      if (std::nearbyint(units) != std::nearbyint(expected[c] * 255.0f) ||
          std::fabs(units - std::nearbyint(units)) > 1e-3f)
        return false;
    } else if (std::bit_cast<uint32_t>(got[c]) != std::bit_cast<uint32_t>(expected[c])) {
      return false;
    }
  }
  return true;
}

namespace {

// Bilinear filtering at normalized u with positions rounded to 2^-bits texel and real-valued
// weights and lerps, in units of 1/255.
glm::dvec4 snappedBilinear(const ShaderProbe& probe, glm::vec2 u, int bits) {
  const glm::ivec2 size = probe.textureSize;
  const double step = std::ldexp(1.0, -bits);
  glm::dvec2 p;
  for (int k = 0; k < 2; ++k)
    p[k] = std::nearbyint((static_cast<double>(u[k]) * size[k] - 0.5) / step) * step;
  const glm::dvec2 base = glm::floor(p), f = p - base;
  const auto at = [&](int dx, int dy) {
    const int i = std::clamp(static_cast<int>(base.x) + dx, 0, size.x - 1);
    const int j = std::clamp(static_cast<int>(base.y) + dy, 0, size.y - 1);
    return glm::dvec4(probe.texels[static_cast<size_t>(j * size.x + i)]);
  };
  const glm::dvec4 row0 = at(0, 0) + (at(1, 0) - at(0, 0)) * f.x;
  const glm::dvec4 row1 = at(0, 1) + (at(1, 1) - at(0, 1)) * f.x;
  return row0 + (row1 - row0) * f.y;
}

}  // namespace

const std::vector<NamedFilter>& filterMembers() {
  static const std::vector<NamedFilter> members = {
      {{.weights = FilterWeights::kFixedPoint8}, "fixed_point_8"},
      {{.weights = FilterWeights::kFixedPoint8, .lerpRounding = LerpRounding::kFloor},
       "fixed_point_8_floor"},
      {{.weights = FilterWeights::kFloat}, "float"},
      {{.weights = FilterWeights::kFloat, .fusedLerp = true}, "float_fused_lerp"},
      {{.weights = FilterWeights::kFloat, .fusedCoordinate = true}, "float_fused_position"},
      {{.weights = FilterWeights::kFloat, .fusedLerp = true, .fusedCoordinate = true},
       "float_fused_lerp_and_position"}};
  return members;
}

namespace {

// The corner-weight members (render/arithmetic.h, Filter): every combination of coordinate bits
// (8 to 24), weight bits (4 to 12), position and corner-product rounding and output, against the
// samples. Returns those that reproduce every sample (at most two: more cannot be told apart)
// and, when none does, the one that misses fewest with its count.
struct CornerSearch {
  std::vector<Filter> fitting;
  Filter closest;
  uint64_t closestMisses = ~uint64_t{0};
};

CornerSearch searchCornerMembers(const std::vector<FilterSample>& sampled,
                                 UnormConversion conversion) {
  CornerSearch search;
  Filter f{.weights = FilterWeights::kFixedPointCorners};
  for (int weightBits = 4; weightBits <= 12; ++weightBits)
    for (int coordinateBits = std::max(8, weightBits); coordinateBits <= 24; ++coordinateBits)
      for (const auto& [position, positionName] : kPositionRoundingNames)
        for (const auto& [corner, cornerName] : kLerpRoundingNames)
          for (const auto& [output, outputName] : kFilterOutputNames) {
            f.weightBits = weightBits;
            f.coordinateBits = coordinateBits;
            f.positionRounding = position;
            f.lerpRounding = corner;
            f.output = output;
            // Counted until it misses more than the closest so far.
            uint64_t missed = 0;
            for (const FilterSample& s : sampled)
              for (size_t i = 0; i < s.out.size() && missed <= search.closestMisses; ++i)
                missed += !reproducesSample(s.probe, i, s.out[i], f, conversion);
            if (missed == 0 && search.fitting.size() < 2) search.fitting.push_back(f);
            if (missed < search.closestMisses) {
              search.closestMisses = missed;
              search.closest = f;
            }
          }
  return search;
}

// "fixed_point_corners_21_8_half_up_nearest_unorm16": coordinate and weight bits, position and
// corner rounding, output.
std::string cornerMemberName(const Filter& f) {
  return "fixed_point_corners_" + std::to_string(f.coordinateBits) + "_" +
         std::to_string(f.weightBits) + "_" +
         std::string(nameOf(kPositionRoundingNames, f.positionRounding)) + "_" +
         std::string(nameOf(kLerpRoundingNames, f.lerpRounding)) + "_" +
         std::string(nameOf(kFilterOutputNames, f.output));
}

}  // namespace

FilterFit fitFilter(const std::vector<FilterSample>& sampled, UnormConversion conversion) {
  FilterFit result;
  result.fit.parameter = "filter";
  result.fit.probe =
      "GL_LINEAR samples: a 16 x 16 RGBA8 texture at 32,768 positions on and beside 1/256-texel "
      "steps, a 24 x 40 one at 16,384 random coordinates";
  if (sampled.size() > 2)
    result.fit.probe +=
        "; and at the cache's sizes, 16384 x 2, 2 x 16384 and 4080 x 4 textures at 8,192 "
        "coordinates each";
  std::string blockTextures;
  for (const FilterSample& s : sampled) {
    if (s.probe.blockFormat == PixelFormat::kUnorm8) continue;
    blockTextures += blockTextures.empty() ? "" : " and ";
    blockTextures += s.probe.blockFormat == PixelFormat::kBc1 ? "BC1" : "BC3";
  }
  if (!blockTextures.empty())
    result.fit.probe += "; " + blockTextures +
                        " textures of 4096 x 8 at 8,192 each, decoded as the pinned decoding "
                        "members say";

  for (const FilterSample& s : sampled) result.fit.probes += s.out.size();
  for (const NamedFilter& member : filterMembers()) {
    uint64_t missed = 0;
    for (const FilterSample& s : sampled)
      for (size_t i = 0; i < s.out.size(); ++i)
        missed += !reproducesSample(s.probe, i, s.out[i], member.filter, conversion);
    result.fit.members.push_back({member.name, missed});
  }
  result.filter = filterMembers()[result.fit.choose()].filter;
  if (!result.fit.pinned) {
    // None of the named members: the corner-weight family's parameters, pinned where exactly one
    // combination reproduces every sample.
    const CornerSearch corners = searchCornerMembers(sampled, conversion);
    const Filter& best = corners.fitting.empty() ? corners.closest : corners.fitting[0];
    result.fit.members.push_back(
        {cornerMemberName(best), corners.fitting.empty() ? corners.closestMisses : uint64_t{0}});
    if (corners.fitting.size() > 1)
      result.fit.members.push_back({cornerMemberName(corners.fitting[1]), 0});
    const size_t chosen = result.fit.choose();
    const size_t named = filterMembers().size();
    if (chosen >= named) result.filter = chosen == named ? best : corners.fitting[1];
    // Two combinations that reproduce every sample: the probe cannot tell them apart.
    if (corners.fitting.size() > 1) result.fit.pinned = false;
  }
  if (result.fit.pinned) {
    result.fit.finding = result.fit.chosen + ", every sample bit for bit (" +
                         result.fit.memberSummary() + " samples)";
    return result;
  }
  // Bounded: the sub-texel precision whose real-valued filter leaves the smallest largest error.
  double best = 1e30;
  for (int bits = 4; bits <= 12; ++bits) {
    double largest = 0;
    for (const FilterSample& s : sampled)
      for (size_t i = 0; i < s.out.size(); ++i) {
        const glm::dvec4 expected = snappedBilinear(s.probe, glm::vec2(s.probe.inputs[i]), bits);
        for (int c = 0; c < 4; ++c)
          largest = std::max(largest, std::fabs(s.out[i][c] * 255.0 - expected[c]));
      }
    if (largest < best) best = largest, result.subTexelBits = bits;
  }
  result.errorUnits = best;
  result.fit.unit = "units of 1/255";
  result.fit.largestResidual = best;
  result.fit.finding = "no member of the family (" + result.fit.memberSummary() +
                       " samples): closest with positions on 2^-" +
                       std::to_string(result.subTexelBits) + " texel, largest error " +
                       std::to_string(best) + " / 255";
  return result;
}

}  // namespace vt::calibrate
