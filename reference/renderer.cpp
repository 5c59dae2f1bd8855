#include "reference/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <thread>

#include "common/parallel_for.h"
#include "reference/lane_shading.h"
#include "reference/linear_filter.h"
#include "reference/result_set_builder.h"
#include "reference/shader_backends.h"
#include "reference/shader_math.h"
#include "reference/visibility.h"
#include "render/cache_state.h"
#include "shader/needbuffer.h"
#include "shader/shader_cpp.h"

namespace vt::reference {
namespace {

using shader::vec2;
using shader::vec4;

using Attributes = PixelAttributes;

}  // namespace

namespace {

// A backend as the result sets read the cache: the indirection entry, then texels of that page.
template <class Backend>
class BackendTexels : public TexelSource {
 public:
  explicit BackendTexels(Backend& backend) : backend_(backend) {}
  glm::uvec4 entry(glm::ivec2 page, int level) override {
    return backend_.vtFetchIndirection(page, level);
  }
  glm::u8vec4 texel(glm::ivec2 position) override { return backend_.fetch8(position); }
  std::array<glm::u8vec4, 2> texelRange(glm::ivec2 position) override {
    return backend_.fetchRange(position);
  }

 private:
  Backend& backend_;
};

// The alternatives one tile found, pixel by pixel, to be gathered in pixel order.
struct TileSets {
  std::vector<std::pair<size_t, uint32_t>> pixels;  // pixel index, number of alternatives
  std::vector<Alternative> alternatives;
};

// Gathers the tiles' alternatives into `sets`, one set per pixel in pixel order, the tiles' copies
// in parallel. `sets` keeps its storage from frame to frame.
void gatherSets(const std::vector<TileSets>& tiles, size_t pixels, unsigned threads,
                ResultSets& sets) {
  sets.offsets.assign(pixels + 1, 0);
  for (const TileSets& tile : tiles)
    for (const auto& [pixel, count] : tile.pixels) sets.offsets[pixel + 1] = count;
  for (size_t i = 0; i < pixels; ++i) sets.offsets[i + 1] += sets.offsets[i];
  sets.alternatives.resize(sets.offsets[pixels]);
  parallelFor(tiles.size(), threads, [&](size_t t) {
    const TileSets& tile = tiles[t];
    size_t next = 0;
    for (const auto& [pixel, count] : tile.pixels) {
      std::copy_n(tile.alternatives.begin() + static_cast<std::ptrdiff_t>(next), count,
                  sets.alternatives.begin() + sets.offsets[pixel]);
      next += count;
    }
  });
}

// Sizes every channel for `viewport` without clearing: the tiles write every pixel. A frame of
// the same size keeps its buffers, so a renderer drawing frame after frame allocates nothing.
void sizeFrame(Frame& frame, Viewport viewport, bool debug) {
  frame.viewport = viewport;
  const size_t pixels = static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
  frame.color.resize(pixels * 4);
  frame.need.resize(pixels);
  frame.depth.resize(pixels);
  frame.triangle.resize(pixels);
  const size_t debugPixels = debug ? pixels : 0;
  frame.uv.resize(debugPixels);
  frame.derivatives.resize(debugPixels);
  frame.lod.resize(debugPixels);
  frame.residentLevel.resize(debugPixels);
}

// What every tile of one frame shares.
struct FrameJob {
  const RenderSettings& settings;
  Viewport viewport;
  const Arithmetic& arithmetic;
  bool debug;
  const std::vector<SetupTriangle>& triangles;
  const Visibility& visibility;
  const PrecisionModel* model;  // null under a pinned model: no result sets
  bool denormalsOnly;           // the model's one free parameter is the denormal mode
  SetShading shading;
  shader::VtParameters parameters;
  glm::uvec4 noNeed;
  // Shade eight pixels at a time (lane_shading.h); not where a pixel's set is the value shaded with
  // denormals the other way (addDenormalSet shades it alone).
  bool lanes;
  Frame& frame;
};

// One worker's shading of a frame: a tile of pixels at a time, its winners from the tile
// rasterizer (visibility.h), then quad by quad, or two quads side by side per SIMD call
// (lane_shading.h). A triangle's planes are evaluated once at its quad's four pixels (helpers
// included) and serve every pixel of the quad that shows it; a quad pair inside one triangle has
// them evaluated at its eight pixels at once. Pixel k of quad (qx, qy) is
// (qx + column, qy + row), column = k & 1, row = k >> 1; window y points up:
//
//     row 1:  2 3    dUV/dx = right - left in the pixel's row
//     row 0:  0 1    dUV/dy = above - below in the pixel's column
template <class Backend, class Source>
class TileShader {
 public:
  static constexpr int kTile = Visibility::kTile;
  using Fragment = typename shader::ShaderLogic<Backend>::VtFragment;

  TileShader(const FrameJob& job, const Source& texture)
      : job_(job),
        denormals_(job.arithmetic.flushDenormals),
        shader_(&texture, job.arithmetic),
        texels_(shader_) {}

  // Shades the tile at (x0, y0); under a model with free parameters, appends each pixel's result
  // set to `sets`.
  void shadeTile(int x0, int y0, TileSets* sets) {
    sets_ = sets;
    if (sets && job_.settings.judged.empty()) {
      // A pixel's set is one alternative mostly; a few more where triangles meet. (Judging a
      // frame, a few pixels of a frame have sets: no room is kept.)
      sets->pixels.reserve(kTile * kTile);
      sets->alternatives.reserve(kTile * kTile * 5 / 4);
    }
    const Viewport v = job_.viewport;
    job_.visibility.tile(x0, y0, tileHits_);
    const auto hitAt = [&](int px, int py) -> const PixelHit& {
      return tileHits_[static_cast<size_t>((px - x0) + kTile * (py - y0))];
    };
    const int step = job_.lanes ? 4 : 2;  // columns of a step: one quad, or two per SIMD call
    for (int qy = y0; qy < std::min(y0 + kTile, v.height); qy += 2)
      for (int qx = x0; qx < std::min(x0 + kTile, v.width); qx += step)
        if (job_.lanes)
          shadeQuadPairInLanes(qx, qy, hitAt);
        else
          shadeQuad(qx, qy, hitAt);
  }

 private:
  // The quads at (qx, qy) and (qx + 2, qy) in one call: lanes 0-3 the left quad's pixels 0-3,
  // lanes 4-7 the right one's.
  template <class HitAt>
  void shadeQuadPairInLanes(int qx0, int qy, const HitAt& hitAt) {
    const Viewport v = job_.viewport;
    // Each lane written once, inactive ones as zeros: value-initialising the whole struct instead
    // compiles to `rep stos`, whose start-up cost was 4% of a pinned frame (perf, terrain).
    LaneFragments in;
    // The triangle each lane's pixel shows: -1 none, -2 outside the viewport.
    std::array<int32_t, lanes::kLanes> shown;
    int32_t only = -1;  // the one triangle every shown pixel shows, if one
    bool single = true;
    for (int lane = 0; lane < lanes::kLanes; ++lane) {
      const int k = lane & 3, px = qx0 + 2 * (lane >> 2) + (k & 1), py = qy + (k >> 1);
      in.u[lane] = in.v[lane] = in.dudx[lane] = in.dvdx[lane] = in.dudy[lane] = in.dvdy[lane] =
          0.0f;
      in.active[lane] = false;
      shown[static_cast<size_t>(lane)] = -2;
      if (px >= v.width || py >= v.height) continue;
      const int32_t triangle = hitAt(px, py).triangle;
      shown[static_cast<size_t>(lane)] = triangle;
      if (triangle < 0) {
        writeEmpty(px, py);
        continue;
      }
      in.active[lane] = true;
      if (only < 0) only = triangle;
      single = single && triangle == only;
    }
    if (only < 0) return;
    // Inside a triangle one lane-wide evaluation serves both quads; where triangles meet, each
    // quad's triangles are evaluated pixel by pixel, once per quad.
    std::array<std::array<Attributes, 4>, 2> sharedAt;
    if (single) {
      float uLanes[lanes::kLanes], vLanes[lanes::kLanes];
      quadPairAttributes(job_.triangles[static_cast<size_t>(only)], qx0, qy, job_.arithmetic,
                         uLanes, vLanes);
      for (size_t lane = 0; lane < lanes::kLanes; ++lane)  // (1/w is not read here)
        sharedAt[lane >> 2][lane & 3] = Attributes{vec2(uLanes[lane], vLanes[lane]), 0.0f};
    }
    for (int half = 0; half < 2; ++half) {
      slots_ = 0;
      for (int k = 0; k < 4; ++k) {
        const int lane = 4 * half + k;
        if (!in.active[lane]) continue;
        const PixelInputs pixel =
            inputsOf(k, single ? sharedAt[static_cast<size_t>(half)]
                               : quadAttributes(shown[static_cast<size_t>(lane)], qx0 + 2 * half,
                                                qy));
        in.u[lane] = pixel.uv.x;
        in.v[lane] = pixel.uv.y;
        in.dudx[lane] = pixel.dUVdx.x;
        in.dvdx[lane] = pixel.dUVdx.y;
        in.dudy[lane] = pixel.dUVdy.x;
        in.dvdy[lane] = pixel.dUVdy.y;
      }
    }
    LaneResults out;
    shadeLanes(static_cast<Backend&>(shader_), job_.arithmetic, job_.parameters,
               job_.settings.needOnly, in, out);
    for (int lane = 0; lane < lanes::kLanes; ++lane) {
      if (!in.active[lane]) continue;
      const int half = lane >> 2, k = lane & 3;
      const int px = qx0 + 2 * half + (k & 1), py = qy + (k >> 1);
      const PixelInputs pixel{vec2(in.u[lane], in.v[lane]), vec2(in.dudx[lane], in.dvdx[lane]),
                              vec2(in.dudy[lane], in.dvdy[lane])};
      const PixelHit& hit = hitAt(px, py);
      const glm::u8vec4 color(out.color[lane][0], out.color[lane][1], out.color[lane][2],
                              out.color[lane][3]);
      writePixel(
          px, py, hit, pixel, color,
          glm::uvec4(out.need[lane][0], out.need[lane][1], out.need[lane][2], out.need[lane][3]),
          out.lod[lane], out.residentLevel[lane]);
      if (job_.model)
        addSet(px, py,
               OracleFragment{hit.triangle, color, pixel.uv, out.neededLevel[lane], out.lod[lane],
                              pixel.dUVdx, pixel.dUVdy});
    }
  }

  // A pixel's shader inputs: its texture coordinates and their fine derivatives.
  struct PixelInputs {
    vec2 uv, dUVdx, dUVdy;
  };

  // Pixel k of a quad whose attributes are `at`: dUV/dx = right - left in its row, dUV/dy =
  // above - below in its column.
  static PixelInputs inputsOf(int k, const std::array<Attributes, 4>& at) {
    const int column = k & 1, row = k >> 1;
    const Attributes left = at[static_cast<size_t>(2 * row)],
                     right = at[static_cast<size_t>(2 * row + 1)];
    const Attributes below = at[static_cast<size_t>(column)],
                     above = at[static_cast<size_t>(2 + column)];
    return {at[static_cast<size_t>(k)].uv, right.uv - left.uv, above.uv - below.uv};
  }

  template <class HitAt>
  void shadeQuad(int qx, int qy, const HitAt& hitAt) {
    slots_ = 0;
    for (int k = 0; k < 4; ++k) {
      const int px = qx + (k & 1), py = qy + (k >> 1);
      if (px >= job_.viewport.width || py >= job_.viewport.height) continue;
      const PixelHit hit = hitAt(px, py);
      if (hit.triangle < 0)
        writeEmpty(px, py);
      else
        shadePixel(px, py, k, hit, quadAttributes(hit.triangle, qx, qy));
    }
  }

  // The triangle's attributes at the quad's four pixels, evaluated once per quad.
  const std::array<Attributes, 4>& quadAttributes(int32_t triangle, int qx, int qy) {
    int slot = 0;
    while (slot < slots_ && quadTriangle_[static_cast<size_t>(slot)] != triangle) ++slot;
    auto& at = quadAttributes_[static_cast<size_t>(slot)];
    if (slot == slots_) {
      quadTriangle_[static_cast<size_t>(slot)] = triangle;
      const SetupTriangle& t = job_.triangles[static_cast<size_t>(triangle)];
      for (int q = 0; q < 4; ++q)
        at[static_cast<size_t>(q)] = attributesAt(t, qx + (q & 1), qy + (q >> 1), job_.arithmetic);
      ++slots_;
    }
    return at;
  }

  size_t indexOf(int px, int py) const {
    return static_cast<size_t>(py) * static_cast<size_t>(job_.viewport.width) +
           static_cast<size_t>(px);
  }

  // Whether the judged frame (RenderSettings::judged) holds the oracle's own value, written, at
  // pixel `index`: identical there (the predicate compareFrames counts by), it needs no set.
  bool judgedIdentical(size_t index) const {
    const RenderSettings::JudgedFrame& judged = job_.settings.judged;
    if (judged.empty()) return false;
    const Frame& frame = job_.frame;
    const glm::uvec4 need(judged.need[index * 4], judged.need[index * 4 + 1],
                          judged.need[index * 4 + 2], judged.need[index * 4 + 3]);
    return need == frame.need[index] &&
           std::equal(frame.color.begin() + static_cast<std::ptrdiff_t>(index * 4),
                      frame.color.begin() + static_cast<std::ptrdiff_t>(index * 4 + 4),
                      judged.color.begin() + static_cast<std::ptrdiff_t>(index * 4));
  }

  // No geometry: the clear values.
  void writeEmpty(int px, int py) {
    Frame& frame = job_.frame;
    const size_t index = indexOf(px, py);
    for (size_t c = 0; c < 4; ++c) frame.color[index * 4 + c] = 0;
    frame.need[index] = job_.noNeed;
    frame.depth[index] = 1.0f;
    frame.triangle[index] = -1;
    if (job_.model && job_.denormalsOnly) {
      // Where the judged frame is identical, no set: gatherSets counts 0.
      if (!judgedIdentical(index)) {
        sets_->alternatives.push_back(Alternative{});  // the clear values, in either mode
        sets_->pixels.emplace_back(index, 1u);
      }
    } else if (job_.model) {
      addSet(px, py, OracleFragment{});
    }
    if (job_.debug) {
      frame.uv[index] = vec2(0.0f);
      frame.derivatives[index] = vec4(0.0f);
      frame.lod[index] = 0.0f;
      frame.residentLevel[index] = -1;
    }
  }

  // The shader at pixel k of its quad, with fine derivatives from the quad's attributes.
  void shadePixel(int px, int py, int k, const PixelHit& hit, const std::array<Attributes, 4>& at) {
    const PixelInputs pixel = inputsOf(k, at);
    const Fragment f =
        job_.settings.needOnly
            ? needOfFragment(pixel.uv, pixel.dUVdx, pixel.dUVdy)
            : shader_.vtShadeFragment(pixel.uv, pixel.dUVdx, pixel.dUVdy, job_.parameters);
    const ColourConversion& conversion = job_.arithmetic.colourConversion;
    const glm::u8vec4 color(toUnorm8(f.color.x, conversion), toUnorm8(f.color.y, conversion),
                            toUnorm8(f.color.z, conversion), toUnorm8(f.color.w, conversion));
    writePixel(px, py, hit, pixel, color, f.need, f.lod, f.residentLevel);
    if (job_.model && job_.denormalsOnly)
      addDenormalSet(px, py, k, hit,
                     OracleFragment{hit.triangle, color, pixel.uv, f.neededLevel, f.lod,
                                    pixel.dUVdx, pixel.dUVdy});
    else if (job_.model)
      addSet(px, py,
             OracleFragment{hit.triangle, color, pixel.uv, f.neededLevel, f.lod, pixel.dUVdx,
                            pixel.dUVdy});
  }

  // A shaded pixel's values into the frame.
  void writePixel(int px, int py, const PixelHit& hit, const PixelInputs& pixel, glm::u8vec4 color,
                  glm::uvec4 need, float lod, int residentLevel) {
    Frame& frame = job_.frame;
    const size_t index = indexOf(px, py);
    for (int c = 0; c < 4; ++c) frame.color[index * 4 + static_cast<size_t>(c)] = color[c];
    frame.need[index] = need;
    frame.depth[index] = hit.depth;
    frame.triangle[index] =
        static_cast<int32_t>(job_.triangles[static_cast<size_t>(hit.triangle)].primitive);
    if (job_.debug) {
      frame.uv[index] = pixel.uv;
      frame.derivatives[index] = vec4(pixel.dUVdx.x, pixel.dUVdx.y, pixel.dUVdy.x, pixel.dUVdy.y);
      frame.lod[index] = lod;
      frame.residentLevel[index] = static_cast<int8_t>(residentLevel);
    }
  }

  // Under a model whose one free parameter is the denormal mode, the pixel's set holds exactly two
  // values: the oracle's own, and the one it computes with denormals treated the other way, its
  // quad's plane evaluation and its shading both. (Triangle setup runs once: for attributes of
  // texture-coordinate scale its values lie far above the denormal range.)
  void addDenormalSet(int px, int py, int k, const PixelHit& hit, const OracleFragment& own) {
    if (judgedIdentical(indexOf(px, py))) return;  // no set: gatherSets counts 0
    const SetupTriangle& t = job_.triangles[static_cast<size_t>(hit.triangle)];
    const Arithmetic& arithmetic = job_.arithmetic;
    const int qx = px & ~1, qy = py & ~1, column = k & 1, row = k >> 1;
    Fragment f;
    vec2 uv;
    {
      const DenormalMode other(!arithmetic.flushDenormals);
      std::array<Attributes, 4> at;
      for (int q = 0; q < 4; ++q)
        at[static_cast<size_t>(q)] = attributesAt(t, qx + (q & 1), qy + (q >> 1), arithmetic);
      uv = at[static_cast<size_t>(k)].uv;
      const vec2 dUVdx =
          at[static_cast<size_t>(2 * row + 1)].uv - at[static_cast<size_t>(2 * row)].uv;
      const vec2 dUVdy =
          at[static_cast<size_t>(2 + column)].uv - at[static_cast<size_t>(column)].uv;
      f = job_.settings.needOnly ? needOfFragment(uv, dUVdx, dUVdy)
                                 : shader_.vtShadeFragment(uv, dUVdx, dUVdy, job_.parameters);
    }
    glm::u8vec4 color;
    for (int c = 0; c < 4; ++c) color[c] = toUnorm8(f.color[c], arithmetic.colourConversion);
    const auto clamped = [&](vec2 v) {
      return glm::vec2(shader_.vtClampOrZero(v.x, 1.0f), shader_.vtClampOrZero(v.y, 1.0f));
    };
    Alternative a;
    a.triangle = static_cast<int32_t>(t.primitive);
    a.levelLo = static_cast<uint8_t>(std::min(own.neededLevel, f.neededLevel));
    a.levelHi = static_cast<uint8_t>(std::max(own.neededLevel, f.neededLevel));
    a.uvLo = glm::min(clamped(own.uv), clamped(uv));
    a.uvHi = glm::max(clamped(own.uv), clamped(uv));
    a.colorLo = a.filterLo = glm::min(own.color, color);
    a.colorHi = a.filterHi = glm::max(own.color, color);
    sets_->alternatives.push_back(a);
    sets_->pixels.emplace_back(indexOf(px, py), 1u);
  }

  // The result set's candidates of the 4 x 4 block that holds (px, py), from one Embree packet:
  // a quad row of the tile meets four blocks, each block two quad rows, so the row's four are kept.
  const Visibility::BlockCandidates& candidatesAt(int px, int py) {
    constexpr int kBlock = Visibility::kBlock;
    const int bx = px - px % kBlock, by = py - py % kBlock;
    const size_t slot = static_cast<size_t>((bx / kBlock) % (kTile / kBlock));
    if (candidateBlocks_[slot].x != bx || candidateBlocks_[slot].y != by) {
      job_.visibility.blockCandidates(bx, by, blockCandidates_[slot]);
      candidateBlocks_[slot] = {bx, by};
    }
    return blockCandidates_[slot];
  }

  // vtNeedOfFragment (src/shader/virtual_texture.glsl): the LOD and the needbuffer entry alone.
  Fragment needOfFragment(vec2 uvIn, vec2 dUVdx, vec2 dUVdy) {
    return shader_.vtNeedOfFragment(uvIn, dUVdx, dUVdy, job_.parameters);
  }

  // The pixel's result set under the model, after the oracle's own value.
  void addSet(int px, int py, const OracleFragment& own) {
    if (judgedIdentical(indexOf(px, py))) return;  // no set: gatherSets counts 0
    const size_t before = sets_->alternatives.size();
    if (!setBuilder_)
      setBuilder_.emplace(*job_.model, job_.shading, job_.triangles, job_.viewport,
                            job_.settings.depthFormat, texels_);
    setBuilder_->append(candidatesAt(px, py), px, py, own, sets_->alternatives);
    sets_->pixels.emplace_back(indexOf(px, py),
                               static_cast<uint32_t>(sets_->alternatives.size() - before));
  }

  const FrameJob& job_;
  const DenormalMode denormals_;
  shader::ShaderLogic<Backend> shader_;
  BackendTexels<shader::ShaderLogic<Backend>> texels_;
  TileSets* sets_ = nullptr;
  std::optional<ResultSetBuilder> setBuilder_;  // made by the first pixel that needs a set
  // The candidates of the blocks of the current row of blocks, by block column.
  std::array<Visibility::BlockCandidates, kTile / Visibility::kBlock> blockCandidates_;
  std::array<glm::ivec2, kTile / Visibility::kBlock> candidateBlocks_{
      glm::ivec2(-1), glm::ivec2(-1), glm::ivec2(-1), glm::ivec2(-1)};
  // The triangles met in the current quad: slots below slots_ hold their attributes.
  std::array<int32_t, 4> quadTriangle_{};
  std::array<std::array<Attributes, 4>, 4> quadAttributes_{};
  int slots_ = 0;
  std::array<PixelHit, kTile * kTile> tileHits_{};  // the tile's winners
};

SetShading setShading(const TextureDescription& d, const RenderSettings& settings,
                      glm::vec2 cacheSize) {
  SetShading shading;
  shading.cacheSide = std::max(cacheSize.x, cacheSize.y);
  shading.pageSize = static_cast<int>(d.pageSize);
  shading.border = static_cast<int>(d.border);
  shading.finestLevel = static_cast<int>(d.finestLevel());
  shading.trilinear = settings.trilinear;
  shading.exactFilter = settings.exactFilter;
  shading.needScaleLog2 = settings.needScaleLog2;
  shading.blockCompressed = isBlockCompressed(d.format);
  return shading;
}

template <class Backend, class Source>
void render(const ClipSpaceMesh& mesh, const Source& texture, const TextureDescription& d,
            glm::vec2 cacheSize, const RenderSettings& settings, Frame& frame) {
  const Viewport viewport = settings.viewport;
  const size_t pixels = static_cast<size_t>(viewport.width) * static_cast<size_t>(viewport.height);
  if (!settings.judged.empty() &&
      (settings.judged.need.size() != pixels * 4 || settings.judged.color.size() != pixels * 4))
    throw std::invalid_argument("renderFrame: the judged frame is not of the viewport's size");
  // The thread limit covers everything: setup, Embree's scene build and the tiles.
  const ThreadLimit parallelism(settings.threads);
  const std::vector<SetupTriangle> triangles = setupTriangles(mesh, viewport, settings.arithmetic);
  // Under a model with free parameters, a coarser sub-pixel grid may cover centres one pixel
  // beyond those the 8-bit grid covers.
  const PrecisionModel* model =
      settings.model && !settings.model->pinned() ? settings.model.get() : nullptr;
  // Judging a frame, few blocks need their sets' candidates: the bins, not Embree's scene.
  const Visibility visibility(triangles, viewport, settings.depthFormat, settings.arithmetic,
                              model ? 1 : 0,
                              settings.judged.empty() ? Visibility::CandidateSearch::kEmbree
                                                      : Visibility::CandidateSearch::kBins);
  sizeFrame(frame, viewport, settings.debugChannels);
  const FrameJob job{settings,
                     viewport,
                     settings.arithmetic,
                     settings.debugChannels,
                     triangles,
                     visibility,
                     model,
                     model != nullptr && model->onlyDenormalsFree(),
                     setShading(d, settings, cacheSize),
                     shaderParameters(d, cacheSize, settings),
                     needClearValue(settings.need8),
                     !(model != nullptr && model->onlyDenormalsFree()) && !settings.scalarShading &&
                         lanes::lanesAvailable(),
                     frame};

  constexpr int kTile = TileShader<Backend, Source>::kTile;
  const int tilesX = (viewport.width + kTile - 1) / kTile,
            tilesY = (viewport.height + kTile - 1) / kTile;
  const size_t tiles = static_cast<size_t>(tilesX) * static_cast<size_t>(tilesY);
  std::vector<TileSets> tileSets(model ? tiles : 0);
  if (model) {
    // A row of tiles per task, so that its set builder keeps what it bounded of each triangle
    // (ResultSetBuilder) from tile to tile.
    parallelFor(static_cast<size_t>(tilesY), settings.threads, [&](size_t row) {
      TileShader<Backend, Source> shader(job, texture);
      for (int column = 0; column < tilesX; ++column)
        shader.shadeTile(column * kTile, static_cast<int>(row) * kTile,
                         &tileSets[row * static_cast<size_t>(tilesX) + static_cast<size_t>(column)]);
    });
  } else {
    parallelFor(tiles, settings.threads, [&](size_t tile) {
      TileShader<Backend, Source> shader(job, texture);
      shader.shadeTile(static_cast<int>(tile % static_cast<size_t>(tilesX)) * kTile,
                       static_cast<int>(tile / static_cast<size_t>(tilesX)) * kTile, nullptr);
    });
  }
  if (model) {
    gatherSets(tileSets, pixels, settings.threads, frame.sets);
    frame.sets.judged = !settings.judged.empty();
  } else
    frame.sets = ResultSets{};
}

}  // namespace

void renderFrame(const ClipSpaceMesh& mesh, const ResidentTexture& texture,
                 const RenderSettings& settings, Frame& frame) {
  const float side = static_cast<float>(texture.description().storedPageSide());
  render<ResidentBackend>(mesh, texture, texture.description(), glm::vec2(side), settings, frame);
}

void renderFrame(const ClipSpaceMesh& mesh, const CacheState& cache, const RenderSettings& settings,
                 Frame& frame) {
  // The oracle samples texels decoded as its arithmetic decodes blocks.
  if (decodesDifferently(cache, settings.arithmetic.blockDecoding)) {
    renderFrame(mesh, withDecoding(cache, settings.arithmetic.blockDecoding), settings, frame);
    return;
  }
  render<CacheBackend>(
      mesh, cache, cache.description,
      glm::vec2(static_cast<float>(cache.widthTexels), static_cast<float>(cache.heightTexels)),
      settings, frame);
}

Frame renderFrame(const ClipSpaceMesh& mesh, const ResidentTexture& texture,
                  const RenderSettings& settings) {
  Frame frame;
  renderFrame(mesh, texture, settings, frame);
  return frame;
}

Frame renderFrame(const ClipSpaceMesh& mesh, const CacheState& cache,
                  const RenderSettings& settings) {
  Frame frame;
  renderFrame(mesh, cache, settings, frame);
  return frame;
}

}  // namespace vt::reference
