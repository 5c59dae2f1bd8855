// Retexturing (thesis 3.3.2): the first-fit page grid, the thesis's layout (our baseline), charts
// of continuously textured faces and their shelf layout, the layout figures, and `vt retexture`
// followed by `vt build` end to end.
//
// The property every layout must have, checked texel by texel: a point of a face samples, through
// its new coordinates, the virtual-texture texel that the area filled with the source texel the
// point sampled through its old coordinates,
//   floor(s' * side) - area.x = floor(s * w) + shiftX - sourceX   (likewise t),
// at points further than 1e-3 texel from a texel boundary (new coordinates are floats: at a side
// of 4096 their rounding moves a point by at most 4096 * 2^-25 = 1.2e-4 texel).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
#include <sstream>

#include "cli/run_command.h"
#include "common/image_file.h"
#include "common/random_draws.h"
#include "format/level_image.h"
#include "format/virtual_texture_reader.h"
#include "retexture/cell_grid.h"
#include "retexture/chart_layout.h"
#include "retexture/face_charts.h"
#include "retexture/layout_quality.h"
#include "retexture/page_grid_layout.h"
#include "retexture/texture_area.h"
#include "scene/missing_texture.h"
#include "scene/obj_scene.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// Scenes built in code.

// A polygon of one texture: corners in order, fan-triangulated into the scene.
struct Polygon {
  uint32_t texture = 0;
  std::vector<glm::vec3> corners = {};
  std::vector<glm::vec2> uvs = {};
};

uint32_t addTexture(TexturedScene& scene, const std::string& name, uint32_t w, uint32_t h) {
  SourceTexture texture;
  texture.name = name;
  texture.file = name + ".png";
  texture.width = w, texture.height = h;
  scene.textures.push_back(texture);
  return static_cast<uint32_t>(scene.textures.size() - 1);
}

// Adds the polygon as one face owning its corners (vertices are not shared between faces).
uint32_t addFace(TexturedScene& scene, const Polygon& polygon) {
  const auto base = static_cast<uint32_t>(scene.positions.size());
  const auto corners = static_cast<uint32_t>(polygon.corners.size());
  scene.faces.push_back({.texture = polygon.texture,
                         .firstIndex = static_cast<uint32_t>(scene.indices.size()),
                         .indexCount = 3 * (corners - 2)});
  scene.positions.insert(scene.positions.end(), polygon.corners.begin(), polygon.corners.end());
  scene.uvs.insert(scene.uvs.end(), polygon.uvs.begin(), polygon.uvs.end());
  for (uint32_t c = 1; c + 1 < corners; ++c)
    scene.indices.insert(scene.indices.end(), {base, base + c, base + c + 1});
  return static_cast<uint32_t>(scene.faces.size() - 1);
}

// The rectangle [x0, x1] x [y0, y1] of the plane z = 0, textured by `map` of its positions.
template <typename Map>
Polygon quadZ(uint32_t texture, float x0, float y0, float x1, float y1, Map map) {
  Polygon quad{.texture = texture, .corners = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}};
  for (const glm::vec3& p : quad.corners) quad.uvs.push_back(map(p));
  return quad;
}

// Uniform in [a, b) from the generator's 32 bits (the standard distributions differ between
// libraries; mt19937's output does not).
double uniform(std::mt19937& rng, double a, double b) {
  return a + (b - a) * (static_cast<double>(rng()) / 4294967296.0);
}

// Random boxes, each side one face or two coplanar halves, with random planar mappings that
// repeat the texture 0.3 to 2.5 times across a side (some rotated in the plane), offset by up to
// 4 repetitions; the second half of a split side is sometimes shifted by whole repetitions.
std::vector<Polygon> randomBoxes(uint32_t boxes, uint32_t textureCount, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<Polygon> polygons;
  for (uint32_t b = 0; b < boxes; ++b) {
    glm::vec3 origin(0.0f), size(0.0f);
    for (int k = 0; k < 3; ++k) {
      origin[k] = static_cast<float>(uniform(rng, -20.0, 20.0));
      size[k] = static_cast<float>(uniform(rng, 0.5, 4.0));
    }
    for (int n = 0; n < 3; ++n)
      for (int far = 0; far < 2; ++far) {
        const int a = (n + 1) % 3, c = (n + 2) % 3;  // the side's axes
        const auto texture = static_cast<uint32_t>(rng() % textureCount);
        const bool rotated = rng() % 3 == 0;
        const double angle = rotated ? uniform(rng, 0.0, 6.283185307179586) : 0.0;
        const double spanA = rotated ? std::max(size[a], size[c]) : size[a];
        const double spanC = rotated ? std::max(size[a], size[c]) : size[c];
        const double kS = uniform(rng, 0.3, 2.5) / spanA, kT = uniform(rng, 0.3, 2.5) / spanC;
        const double offS = uniform(rng, -4.0, 4.0), offT = uniform(rng, -4.0, 4.0);
        const auto map = [&](glm::vec3 p) {
          const double da = double{p[a]} - origin[a], dc = double{p[c]} - origin[c];
          return glm::vec2(offS + kS * (std::cos(angle) * da + std::sin(angle) * dc),
                           offT + kT * (-std::sin(angle) * da + std::cos(angle) * dc));
        };
        const auto corner = [&](float pa, float pc) {
          glm::vec3 p = origin;
          p[n] = origin[n] + (far ? size[n] : 0.0f);
          p[a] = pa, p[c] = pc;
          return p;
        };
        const float a0 = origin[a], a1 = origin[a] + size[a];
        const float c0 = origin[c], c1 = origin[c] + size[c];
        const auto side = [&](float from, float to, glm::vec2 shift) {
          Polygon polygon{
              .texture = texture,
              .corners = {corner(from, c0), corner(to, c0), corner(to, c1), corner(from, c1)}};
          for (const glm::vec3& p : polygon.corners) polygon.uvs.push_back(map(p) + shift);
          polygons.push_back(std::move(polygon));
        };
        if (rng() % 2 == 0) {
          side(a0, a1, glm::vec2(0.0f));
          continue;
        }
        // Two halves sharing the corners at `middle` bit for bit.
        const auto middle = static_cast<float>(a0 + size[a] * uniform(rng, 0.3, 0.7));
        side(a0, middle, glm::vec2(0.0f));
        const bool shifted = rng() % 2 == 0;
        const glm::vec2 shift = shifted ? drawPoint([&] { return static_cast<float>(rng() % 5) - 2.0f; })
                                        : glm::vec2(0.0f);
        side(middle, a1, shift);
      }
  }
  return polygons;
}

TexturedScene randomBoxScene(uint32_t boxes, uint32_t seed) {
  TexturedScene scene;
  scene.name = "boxes";
  addTexture(scene, "square", 64, 64);
  addTexture(scene, "wide", 128, 32);
  addTexture(scene, "odd", 100, 60);
  addTexture(scene, "tiny", 17, 9);
  for (const Polygon& polygon : randomBoxes(boxes, 4, seed)) addFace(scene, polygon);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// The properties every layout must have.

glm::i64vec2 shiftOf(const Retexturing& layout, size_t face) {
  return layout.faceShift.empty() ? glm::i64vec2(0) : layout.faceShift[face];
}

// Every face has an area of its texture; areas lie inside the texture and do not overlap.
void expectAreasValid(const TexturedScene& scene, const Retexturing& layout) {
  ASSERT_EQ(layout.faceArea.size(), scene.faces.size());
  ASSERT_TRUE(layout.faceShift.empty() || layout.faceShift.size() == scene.faces.size());
  ASSERT_EQ(layout.side % layout.pageSize, 0u);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    ASSERT_LT(layout.faceArea[f], layout.areas.size()) << "face " << f;
    EXPECT_EQ(layout.areas[layout.faceArea[f]].texture, scene.faces[f].texture) << "face " << f;
  }
  for (size_t i = 0; i < layout.areas.size(); ++i) {
    const TextureArea& a = layout.areas[i];
    ASSERT_GT(a.width, 0u);
    ASSERT_GT(a.height, 0u);
    ASSERT_LE(a.x + a.width, layout.side) << "area " << i;
    ASSERT_LE(a.y + a.height, layout.side) << "area " << i;
    for (size_t j = i + 1; j < layout.areas.size(); ++j) {
      const TextureArea& b = layout.areas[j];
      const bool apart = a.x + a.width <= b.x || b.x + b.width <= a.x || a.y + a.height <= b.y ||
                         b.y + b.height <= a.y;
      ASSERT_TRUE(apart) << "areas " << i << " and " << j << " overlap";
    }
  }
}

// Every new coordinate lies in its face's area (to 1e-3 texel).
void expectUvsInsideAreas(const TexturedScene& scene, const Retexturing& layout,
                          const std::vector<glm::vec2>& uvs) {
  const auto side = static_cast<double>(layout.side);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TextureArea& area = layout.areas[layout.faceArea[f]];
    const TexturedFace& face = scene.faces[f];
    for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
      const glm::dvec2 texel = glm::dvec2(uvs[scene.indices[i]]) * side;
      ASSERT_GE(texel.x, static_cast<double>(area.x) - 1e-3) << "face " << f;
      ASSERT_LE(texel.x, static_cast<double>(area.x + area.width) + 1e-3) << "face " << f;
      ASSERT_GE(texel.y, static_cast<double>(area.y) - 1e-3) << "face " << f;
      ASSERT_LE(texel.y, static_cast<double>(area.y + area.height) + 1e-3) << "face " << f;
    }
  }
}

bool nearTexelBoundary(double texel) { return std::abs(texel - std::round(texel)) < 1e-3; }

// The texel-exactness property of the file comment at random interior points of every triangle;
// returns how many points were checked.
uint64_t expectTexelExact(const TexturedScene& scene, const Retexturing& layout,
                          const std::vector<glm::vec2>& uvs) {
  std::mt19937 rng(11);
  const auto side = static_cast<double>(layout.side);
  uint64_t checked = 0;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TexturedFace& face = scene.faces[f];
    const TextureArea& area = layout.areas[layout.faceArea[f]];
    const SourceTexture& texture = scene.textures[face.texture];
    const glm::i64vec2 shift = shiftOf(layout, f);
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      for (int k = 0; k < 16; ++k) {
        double b1 = uniform(rng, 0.0, 1.0), b2 = uniform(rng, 0.0, 1.0);
        if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
        const double b[3] = {1.0 - b1 - b2, b1, b2};
        glm::dvec2 st(0.0), newSt(0.0);
        for (int c = 0; c < 3; ++c) {
          st += b[c] * glm::dvec2(scene.uvs[scene.indices[t + c]]);
          newSt += b[c] * glm::dvec2(uvs[scene.indices[t + c]]);
        }
        const double u = st.x * texture.width, v = st.y * texture.height;
        if (nearTexelBoundary(u) || nearTexelBoundary(v)) continue;
        const int64_t expectedX = static_cast<int64_t>(std::floor(u)) + shift.x - area.sourceX;
        const int64_t expectedY = static_cast<int64_t>(std::floor(v)) + shift.y - area.sourceY;
        const int64_t actualX =
            static_cast<int64_t>(std::floor(newSt.x * side)) - static_cast<int64_t>(area.x);
        const int64_t actualY =
            static_cast<int64_t>(std::floor(newSt.y * side)) - static_cast<int64_t>(area.y);
        EXPECT_EQ(actualX, expectedX)
            << "face " << f << " at source texel (" << u << ", " << v << ")";
        EXPECT_EQ(actualY, expectedY)
            << "face " << f << " at source texel (" << u << ", " << v << ")";
        if (actualX != expectedX || actualY != expectedY) return checked;
        ++checked;
      }
    }
  }
  return checked;
}

void expectValidLayout(const TexturedScene& scene, const Retexturing& layout) {
  ASSERT_NO_FATAL_FAILURE(expectAreasValid(scene, layout));
  const std::vector<glm::vec2> uvs = retexturedUvs(scene, layout);
  ASSERT_EQ(uvs.size(), scene.uvs.size());
  ASSERT_NO_FATAL_FAILURE(expectUvsInsideAreas(scene, layout, uvs));
  // Sixteen points per triangle, a few near texel boundaries skipped.
  size_t triangles = 0;
  for (const TexturedFace& face : scene.faces) triangles += face.indexCount / 3;
  EXPECT_GT(expectTexelExact(scene, layout, uvs), 15 * triangles);
}

// ---------------------------------------------------------------------------------------------
// CellGrid

TEST(CellGrid, FirstFitTakesTheFirstFreeBlockInRowMajorOrder) {
  CellGrid grid(4);
  const auto at = [](std::optional<CellGrid::Cell> cell) {
    return cell ? std::pair<int, int>(int(cell->x), int(cell->y)) : std::pair<int, int>(-1, -1);
  };
  EXPECT_EQ(at(grid.firstFit(1, 1)), std::make_pair(0, 0));
  grid.occupy({0, 0}, 2, 1);
  EXPECT_EQ(at(grid.firstFit(1, 1)), std::make_pair(2, 0));
  EXPECT_EQ(at(grid.firstFit(2, 1)), std::make_pair(2, 0));
  EXPECT_EQ(at(grid.firstFit(3, 1)), std::make_pair(0, 1));  // row 0 has two free cells left
  EXPECT_EQ(at(grid.firstFit(2, 2)), std::make_pair(2, 0));
  EXPECT_EQ(at(grid.firstFit(4, 3)), std::make_pair(0, 1));
  EXPECT_EQ(at(grid.firstFit(5, 1)), std::make_pair(-1, -1));  // wider than the grid
  EXPECT_EQ(at(grid.firstFit(4, 4)), std::make_pair(-1, -1));
}

TEST(CellGrid, FirstFitSkipsBlocksHoldingAnOccupiedCell) {
  CellGrid grid(4);
  grid.occupy({1, 1}, 1, 1);
  const auto fit = grid.firstFit(2, 2);
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->x, 2u);  // (0, 0) and (1, 0) would cover (1, 1)
  EXPECT_EQ(fit->y, 0u);
  grid.occupy(*fit, 2, 2);
  const auto next = grid.firstFit(2, 2);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->x, 0u);
  EXPECT_EQ(next->y, 2u);
  grid.occupy(*next, 2, 2);
  grid.occupy({2, 2}, 2, 2);
  // What is left: (0, 0), (1, 0), (0, 1).
  EXPECT_FALSE(grid.firstFit(2, 2));
  const auto column = grid.firstFit(1, 2);
  ASSERT_TRUE(column);
  EXPECT_EQ(column->x, 0u);
  EXPECT_EQ(column->y, 0u);
  grid.occupy({0, 0}, 2, 1);
  grid.occupy({0, 1}, 1, 1);
  EXPECT_FALSE(grid.firstFit(1, 1));
}

TEST(CellGrid, GrowKeepsPlacedCells) {
  CellGrid grid(2);
  grid.occupy({0, 0}, 2, 1);
  grid.occupy({0, 1}, 1, 1);
  EXPECT_FALSE(grid.firstFit(2, 1));
  grid.grow(4);
  EXPECT_EQ(grid.side(), 4u);
  const auto one = grid.firstFit(1, 1);
  ASSERT_TRUE(one);
  EXPECT_EQ(one->x, 2u);  // row 0 has grown two free cells
  EXPECT_EQ(one->y, 0u);
  const auto wide = grid.firstFit(3, 1);
  ASSERT_TRUE(wide);
  EXPECT_EQ(wide->x, 1u);  // (0, 1) is still occupied
  EXPECT_EQ(wide->y, 1u);
  const auto full = grid.firstFit(4, 1);
  ASSERT_TRUE(full);
  EXPECT_EQ(full->x, 0u);
  EXPECT_EQ(full->y, 2u);
  grid.occupy({2, 0}, 2, 1);  // row 0 is now full
  const auto hole = grid.firstFit(1, 1);
  ASSERT_TRUE(hole);
  EXPECT_EQ(hole->x, 1u);  // the old grid's one free cell
  EXPECT_EQ(hole->y, 1u);
  const auto next = grid.firstFit(2, 2);
  ASSERT_TRUE(next);
  EXPECT_EQ(next->x, 1u);
  EXPECT_EQ(next->y, 1u);
}

// ---------------------------------------------------------------------------------------------
// PageGridLayout: the thesis's layout

TEST(PageGridLayout, CopiesWholeRepetitionsIntoWholePageCells) {
  TexturedScene scene;
  scene.name = "grid";
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  // s in [0.25, 2.5]: repetitions 0, 1 and 2 -> 192 texels, 2 cells of 128; t in [0.25, 0.75].
  addFace(scene, quadZ(texture, 0, 0, 2.25f, 0.5f,
                       [](glm::vec3 p) { return glm::vec2(0.25f + p.x, 0.25f + p.y); }));
  // s in [-1.5, -0.5]: repetitions -2 and -1 (sourceX -128); t in [1.25, 1.75]: repetition 1.
  addFace(scene, quadZ(texture, 0, 0, 1, 0.5f,
                       [](glm::vec3 p) { return glm::vec2(-1.5f + p.x, 1.25f + p.y); }));
  const Retexturing layout = layoutOnPageGrid(scene, 128);
  EXPECT_EQ(layout.method, "baseline");
  EXPECT_EQ(layout.pageSize, 128u);
  EXPECT_EQ(layout.side, 256u);  // two cells across: the one-cell grid doubled
  ASSERT_EQ(layout.areas.size(), 2u);
  EXPECT_EQ(layout.faceArea, (std::vector<uint32_t>{0, 1}));
  const TextureArea& a = layout.areas[0];
  EXPECT_EQ(a.width, 192u);
  EXPECT_EQ(a.height, 64u);
  EXPECT_EQ(a.sourceX, 0);
  EXPECT_EQ(a.sourceY, 0);
  EXPECT_EQ(a.x, 0u);
  EXPECT_EQ(a.y, 0u);
  const TextureArea& b = layout.areas[1];
  EXPECT_EQ(b.width, 128u);
  EXPECT_EQ(b.height, 64u);
  EXPECT_EQ(b.sourceX, -128);
  EXPECT_EQ(b.sourceY, 64);
  EXPECT_EQ(b.x, 0u);  // the first free cell, row-major: (1, 0) is the first area's second cell
  EXPECT_EQ(b.y, 128u);

  // s' = (s * w - sourceX + x) / side, t' = (t * h - sourceY + y) / side.
  const std::vector<glm::vec2> uvs = retexturedUvs(scene, layout);
  EXPECT_FLOAT_EQ(uvs[0].x, 16.0f / 256);   // s = 0.25
  EXPECT_FLOAT_EQ(uvs[1].x, 160.0f / 256);  // s = 2.5
  EXPECT_FLOAT_EQ(uvs[0].y, 16.0f / 256);
  EXPECT_FLOAT_EQ(uvs[2].y, 48.0f / 256);   // t = 0.75
  EXPECT_FLOAT_EQ(uvs[4].x, 32.0f / 256);   // s = -1.5: (-96 + 128 + 0) / 256
  EXPECT_FLOAT_EQ(uvs[5].x, 96.0f / 256);   // s = -0.5
  EXPECT_FLOAT_EQ(uvs[4].y, 144.0f / 256);  // t = 1.25: (80 - 64 + 128) / 256
  EXPECT_FLOAT_EQ(uvs[6].y, 176.0f / 256);  // t = 1.75
  for (size_t v = 0; v < scene.uvs.size(); ++v) {
    const TextureArea& area = layout.areas[v < 4 ? 0 : 1];
    const double s = scene.uvs[v].x, t = scene.uvs[v].y;
    EXPECT_NEAR(uvs[v].x, (s * 64 - double(area.sourceX) + double(area.x)) / 256, 1e-7) << v;
    EXPECT_NEAR(uvs[v].y, (t * 64 - double(area.sourceY) + double(area.y)) / 256, 1e-7) << v;
  }
}

TEST(PageGridLayout, GridDoublesWhenNoBlockIsFree) {
  TexturedScene scene;
  scene.name = "five";
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  for (int f = 0; f < 5; ++f)
    addFace(scene, quadZ(texture, 0, 0, 0.8f, 0.8f,
                         [](glm::vec3 p) { return glm::vec2(0.1f + p.x, 0.1f + p.y); }));
  const Retexturing layout = layoutOnPageGrid(scene, 128);
  // One cell each: 1 cell, doubled to 2 x 2 for the second face, to 4 x 4 for the fifth.
  EXPECT_EQ(layout.side, 512u);
  ASSERT_EQ(layout.areas.size(), 5u);
  const uint64_t x[] = {0, 128, 0, 128, 256}, y[] = {0, 0, 128, 128, 0};
  for (size_t f = 0; f < 5; ++f) {
    EXPECT_EQ(layout.areas[f].x, x[f]) << f;
    EXPECT_EQ(layout.areas[f].y, y[f]) << f;
    EXPECT_EQ(layout.areas[f].width, 64u) << f;
  }
}

TEST(PageGridLayout, RandomBoxesGetExactDisjointPageAlignedAreas) {
  const TexturedScene scene = randomBoxScene(30, 1);
  const Retexturing layout = layoutOnPageGrid(scene, 64);
  ASSERT_NO_FATAL_FAILURE(expectValidLayout(scene, layout));
  EXPECT_EQ(layout.areas.size(), scene.faces.size());  // one copy per face
  EXPECT_LE(layout.side, 4096u);
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TextureArea& area = layout.areas[layout.faceArea[f]];
    const SourceTexture& texture = scene.textures[area.texture];
    EXPECT_EQ(area.x % 64, 0u) << f;
    EXPECT_EQ(area.y % 64, 0u) << f;
    EXPECT_EQ(area.width % texture.width, 0u) << f;
    EXPECT_EQ(area.height % texture.height, 0u) << f;
    EXPECT_EQ(area.sourceX % int64_t{texture.width}, 0) << f;
    EXPECT_EQ(area.sourceY % int64_t{texture.height}, 0) << f;
  }
}

// ---------------------------------------------------------------------------------------------
// FaceCharts: which faces share an area

// s = x / 2, t = y / 2 on a 64 x 64 texture: 32 texels per unit.
glm::vec2 halfMap(glm::vec3 p) { return glm::vec2(0.5f * p.x, 0.5f * p.y); }

TEST(FaceCharts, CoplanarNeighboursWithOneMappingShareAChart) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  addFace(scene, quadZ(texture, 1, 0, 2, 1, halfMap));
  const std::vector<Chart> charts = buildCharts(scene, {});
  ASSERT_EQ(charts.size(), 1u);
  EXPECT_EQ(charts[0].faces, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(charts[0].offsets, (std::vector<glm::i64vec2>{{0, 0}, {0, 0}}));
  // Texels [0, 64) x [0, 32) and the margin of 1.
  EXPECT_EQ(charts[0].x0, -1);
  EXPECT_EQ(charts[0].x1, 65);
  EXPECT_EQ(charts[0].y0, -1);
  EXPECT_EQ(charts[0].y1, 33);
  EXPECT_EQ(charts[0].texture, texture);
}

TEST(FaceCharts, NeighbourShiftedByWholeRepetitionsJoinsWithThatShift) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  // The same mapping with s + 3: 3 * 64 texels further on in the unrolled space.
  addFace(scene, quadZ(texture, 1, 0, 2, 1,
                       [](glm::vec3 p) { return halfMap(p) + glm::vec2(3.0f, 0.0f); }));
  const std::vector<Chart> charts = buildCharts(scene, {});
  ASSERT_EQ(charts.size(), 1u);
  EXPECT_EQ(charts[0].offsets, (std::vector<glm::i64vec2>{{0, 0}, {-192, 0}}));
  EXPECT_EQ(charts[0].x0, -1);
  EXPECT_EQ(charts[0].x1, 65);

  const Retexturing layout = layoutCharts(scene, 128);
  ASSERT_EQ(layout.areas.size(), 1u);
  EXPECT_EQ(layout.faceArea, (std::vector<uint32_t>{0, 0}));
  ASSERT_EQ(layout.faceShift.size(), 2u);
  EXPECT_EQ(layout.faceShift[0], glm::i64vec2(0, 0));
  EXPECT_EQ(layout.faceShift[1], glm::i64vec2(-3 * 64, 0));
  EXPECT_EQ(layout.areas[0].width, 66u);
  EXPECT_EQ(layout.areas[0].sourceX, -1);
  // Continuous: the shared corners (1, 0) and (1, 1) get the same new coordinates in both faces.
  const std::vector<glm::vec2> uvs = retexturedUvs(scene, layout);
  EXPECT_EQ(uvs[1], uvs[4]);
  EXPECT_EQ(uvs[2], uvs[7]);
  EXPECT_FLOAT_EQ(uvs[1].x, (32.0f + 1.0f + float(layout.areas[0].x)) / float(layout.side));
  ASSERT_NO_FATAL_FAILURE(expectValidLayout(scene, layout));

  // The other way round: the lower face shifted, the higher one joins with +3 repetitions.
  TexturedScene swapped;
  addTexture(swapped, "wall", 64, 64);
  addFace(swapped, quadZ(texture, 0, 0, 1, 1,
                         [](glm::vec3 p) { return halfMap(p) + glm::vec2(3.0f, 0.0f); }));
  addFace(swapped, quadZ(texture, 1, 0, 2, 1, halfMap));
  const Retexturing swappedLayout = layoutCharts(swapped, 128);
  ASSERT_EQ(swappedLayout.areas.size(), 1u);
  EXPECT_EQ(swappedLayout.faceShift[1], glm::i64vec2(3 * 64, 0));
  EXPECT_EQ(swappedLayout.areas[0].sourceX, 3 * 64 - 1);
  const std::vector<glm::vec2> swappedUvs = retexturedUvs(swapped, swappedLayout);
  EXPECT_EQ(swappedUvs[1], swappedUvs[4]);
  EXPECT_EQ(swappedUvs[2], swappedUvs[7]);
}

TEST(FaceCharts, FacesOnPerpendicularPlanesStayApart) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  // The plane x = 1, its s continuing the first face's along the shared edge (a fold).
  Polygon fold{.texture = texture, .corners = {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}};
  for (const glm::vec3& p : fold.corners) fold.uvs.push_back({0.5f + 0.5f * p.z, 0.5f * p.y});
  addFace(scene, fold);
  EXPECT_EQ(buildCharts(scene, {}).size(), 2u);
}

TEST(FaceCharts, FacesOfDifferentTexturesStayApart) {
  TexturedScene scene;
  const uint32_t wall = addTexture(scene, "wall", 64, 64);
  const uint32_t floor = addTexture(scene, "floor", 64, 64);
  addFace(scene, quadZ(wall, 0, 0, 1, 1, halfMap));
  addFace(scene, quadZ(floor, 1, 0, 2, 1, halfMap));
  const std::vector<Chart> charts = buildCharts(scene, {});
  ASSERT_EQ(charts.size(), 2u);
  EXPECT_EQ(charts[0].texture, wall);
  EXPECT_EQ(charts[1].texture, floor);
}

TEST(FaceCharts, FacesWithADifferentMappingScaleStayApart) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  // Continuous along the shared edge (s = 0.5 at x = 1) but 16 texels per unit instead of 32.
  addFace(scene, quadZ(texture, 1, 0, 2, 1,
                       [](glm::vec3 p) { return glm::vec2(0.25f + 0.25f * p.x, 0.5f * p.y); }));
  EXPECT_EQ(buildCharts(scene, {}).size(), 2u);
}

TEST(FaceCharts, SlackRuleBlocksAnLShapedMerge) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  addFace(scene, quadZ(texture, 1, 0, 2, 1, halfMap));
  addFace(scene, quadZ(texture, 0, 1, 1, 2, halfMap));
  // Faces 0 and 1 make a 66 x 34 chart; adding face 2 (34 x 34) would make it 66 x 66 = 4356
  // texels, more than 1.1 * (66 * 34 + 34 * 34) = 3740.
  const std::vector<Chart> charts = buildCharts(scene, {});
  ASSERT_EQ(charts.size(), 2u);
  EXPECT_EQ(charts[0].faces, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(charts[1].faces, (std::vector<uint32_t>{2}));
  // With enough slack, the L is one chart.
  const std::vector<Chart> loose = buildCharts(scene, {.slack = 0.3});
  ASSERT_EQ(loose.size(), 1u);
  EXPECT_EQ(loose[0].width(), 66u);
  EXPECT_EQ(loose[0].height(), 66u);
}

TEST(FaceCharts, MaxSideBlocksAMerge) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  addFace(scene, quadZ(texture, 1, 0, 2, 1, halfMap));
  EXPECT_EQ(buildCharts(scene, {.maxSide = 65}).size(), 2u);
  EXPECT_EQ(buildCharts(scene, {.maxSide = 66}).size(), 1u);
}

TEST(FaceCharts, CoplanarFacesTouchingAtOneVertexJoinWithoutSharingTexels) {
  // One plane, one affine map: the map is one-to-one, so the two faces' texels stay apart.
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, halfMap));
  addFace(scene, quadZ(texture, 1, 1, 2, 2, halfMap));
  EXPECT_EQ(buildCharts(scene, {}).size(), 2u);  // the L's corners exceed the default slack
  const std::vector<Chart> charts = buildCharts(scene, {.slack = 100.0});
  ASSERT_EQ(charts.size(), 1u);
  const TexelBounds a = faceTexelBounds(scene, scene.faces[0]);
  const TexelBounds b = faceTexelBounds(scene, scene.faces[1]);
  EXPECT_TRUE(a.u1 <= b.u0 || b.u1 <= a.u0 || a.v1 <= b.v0 || b.v1 <= a.v0);
}

// ---------------------------------------------------------------------------------------------
// ChartLayout: our layout

TEST(ChartLayout, RandomBoxesGetExactDisjointAreas) {
  const TexturedScene scene = randomBoxScene(30, 1);
  const Retexturing layout = layoutCharts(scene, 64);
  EXPECT_EQ(layout.method, "charts");
  ASSERT_NO_FATAL_FAILURE(expectValidLayout(scene, layout));
  // Split sides joined (some with a shift), so fewer areas than faces.
  EXPECT_LT(layout.areas.size(), scene.faces.size());
  size_t shifted = 0;
  for (const glm::i64vec2& shift : layout.faceShift) shifted += shift != glm::i64vec2(0) ? 1 : 0;
  EXPECT_GT(shifted, 0u);
  // Charts hold only what their faces span: far fewer texels than the baseline's copies.
  EXPECT_LT(layout.side, layoutOnPageGrid(scene, 64).side);
}

TEST(ChartLayout, ManySeedsAndPageSizes) {
  for (const uint32_t seed : {2u, 3u, 4u})
    for (const uint32_t pageSize : {16u, 128u}) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << ", page size " << pageSize);
      const TexturedScene scene = randomBoxScene(12, seed);
      ASSERT_NO_FATAL_FAILURE(expectValidLayout(scene, layoutCharts(scene, pageSize)));
      ASSERT_NO_FATAL_FAILURE(expectValidLayout(scene, layoutOnPageGrid(scene, pageSize)));
    }
}

TEST(ChartLayout, StartsAtTheSmallestSideHoldingAllCharts) {
  TexturedScene scene;
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  // One 64 x 64 texel face: a 66 x 66 chart, in a 128 texture with page size 128, at (0, 0).
  addFace(scene, quadZ(texture, 0, 0, 2, 2, halfMap));
  const Retexturing layout = layoutCharts(scene, 128);
  EXPECT_EQ(layout.side, 128u);
  ASSERT_EQ(layout.areas.size(), 1u);
  EXPECT_EQ(layout.areas[0].x, 0u);
  EXPECT_EQ(layout.areas[0].y, 0u);
  EXPECT_EQ(layout.areas[0].width, 66u);
  EXPECT_EQ(layout.areas[0].sourceX, -1);
  EXPECT_EQ(layout.areas[0].sourceY, -1);
  // With pages of 32 the 4356 texels need 128 x 128 as well (64 x 64 holds 4096).
  EXPECT_EQ(layoutCharts(scene, 32).side, 128u);
}

// ---------------------------------------------------------------------------------------------
// LayoutQuality

// One face covering texels [0, 64)^2 of a 64 x 64 texture exactly once.
TexturedScene oneSquareFace() {
  TexturedScene scene;
  scene.name = "square";
  const uint32_t texture = addTexture(scene, "wall", 64, 64);
  addFace(scene, quadZ(texture, 0, 0, 1, 1, [](glm::vec3 p) { return glm::vec2(p.x, p.y); }));
  return scene;
}

LayoutQuality measureHandLayout(const TexturedScene& scene, uint64_t side, uint64_t x, uint64_t y) {
  Retexturing layout;
  layout.pageSize = 128;
  layout.side = side;
  layout.areas.push_back({.texture = 0, .x = x, .y = y, .width = 64, .height = 64});
  layout.faceArea = {0};
  return measureLayout(scene, layout, retexturedUvs(scene, layout));
}

TEST(LayoutQuality, OneFaceInOnePageOfTheBaseline) {
  const TexturedScene scene = oneSquareFace();
  const Retexturing layout = layoutOnPageGrid(scene, 128);
  ASSERT_EQ(layout.side, 128u);
  const LayoutQuality quality = measureLayout(scene, layout, retexturedUvs(scene, layout));
  EXPECT_EQ(quality.finestPages, 1u);
  EXPECT_EQ(quality.allPages, 1u);  // one level
  EXPECT_EQ(quality.referencedTexels, 64u * 64);
  EXPECT_DOUBLE_EQ(quality.referencedFraction, 0.25);
}

TEST(LayoutQuality, CountsEveryLevelsAncestors) {
  const TexturedScene scene = oneSquareFace();
  // Side 512, pages of 128: levels 0..2. The area in finest page (1, 2): it, (0, 1), (0, 0).
  LayoutQuality quality = measureHandLayout(scene, 512, 128, 256);
  EXPECT_EQ(quality.finestPages, 1u);
  EXPECT_EQ(quality.allPages, 3u);
  EXPECT_EQ(quality.referencedTexels, 4096u);
  EXPECT_DOUBLE_EQ(quality.referencedFraction, 0.25);
  // Across pages (0, 2) and (1, 2): both, (0, 1), (0, 0).
  quality = measureHandLayout(scene, 512, 96, 256);
  EXPECT_EQ(quality.finestPages, 2u);
  EXPECT_EQ(quality.allPages, 4u);
  EXPECT_EQ(quality.referencedTexels, 4096u);
  EXPECT_DOUBLE_EQ(quality.referencedFraction, 0.125);
}

TEST(LayoutQuality, CountsEveryLevelForTheTopLeftPage) {
  const TexturedScene scene = oneSquareFace();
  // Finest page (0, 0) of three levels: it, its parent (0, 0) on level 1, the root.
  LayoutQuality quality = measureHandLayout(scene, 512, 0, 0);
  EXPECT_EQ(quality.finestPages, 1u);
  EXPECT_EQ(quality.allPages, 3u);
  // Pages (0, 0) and (1, 0) of level 2: both, then one page on each of levels 1 and 0.
  quality = measureHandLayout(scene, 512, 96, 0);
  EXPECT_EQ(quality.finestPages, 2u);
  EXPECT_EQ(quality.allPages, 4u);
}

// ---------------------------------------------------------------------------------------------
// RetextureOutputs: `vt retexture` then `vt build`, texel by texel

struct RgbImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> texels;  // RGB
};

// Texels that differ from their neighbours in every channel, so a shifted copy cannot pass.
RgbImage rgbPattern(uint32_t width, uint32_t height, uint32_t seed) {
  RgbImage image{width, height, std::vector<uint8_t>(size_t{width} * height * 3)};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (uint32_t c = 0; c < 3; ++c)
        image.texels[(size_t{y} * width + x) * 3 + c] =
            static_cast<uint8_t>(seed * 101 + x * 13 + y * 59 + c * 97);
  return image;
}

// missing_texture.h's checker: magenta and black squares of 8 texels.
RgbImage checker() {
  RgbImage image{kMissingTextureSide, kMissingTextureSide, {}};
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const bool magenta = (x / 8 + y / 8) % 2 == 0;
      image.texels.insert(image.texels.end(),
                          {uint8_t(magenta ? 255 : 0), 0, uint8_t(magenta ? 255 : 0)});
    }
  return image;
}

int64_t floorMod(int64_t a, int64_t m) { return ((a % m) + m) % m; }

class RetextureOutputs : public ::testing::Test {
 protected:
  test::CommandResult vt(const std::vector<std::string>& args) {
    return test::runCommand(VT_EXECUTABLE, args, dir_.path());
  }

  // Random boxes as an OBJ scene of three textures and a material without map_Kd (the checker).
  std::filesystem::path writeScene() {
    const std::pair<uint32_t, uint32_t> sizes[] = {{32, 32}, {48, 20}, {16, 64}};
    std::ostringstream mtl, obj;
    for (uint32_t t = 0; t < 3; ++t) {
      const std::string name = std::string("tex").append(std::to_string(t));
      images_[name + ".png"] = rgbPattern(sizes[t].first, sizes[t].second, t + 1);
      const RgbImage& image = images_[name + ".png"];
      writeImage8(dir_ / (name + ".png"), image.width, image.height, 3,
                  std::as_bytes(std::span(image.texels)));
      mtl << "newmtl m" << t << "\nmap_Kd " << name << ".png\n";
    }
    mtl << "newmtl plain\nKd 0.5 0.5 0.5\n";
    images_["missing_texture.png"] = checker();
    std::ofstream(dir_ / "scene.mtl") << mtl.str();

    obj.precision(9);
    obj << "mtllib scene.mtl\n";
    uint32_t vertices = 0;
    for (const Polygon& polygon : randomBoxes(6, 4, 5)) {
      for (const glm::vec3& p : polygon.corners)
        obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
      for (const glm::vec2& st : polygon.uvs) obj << "vt " << st.x << ' ' << 1.0f - st.y << '\n';
      obj << "usemtl "
          << (polygon.texture < 3 ? std::string("m").append(std::to_string(polygon.texture))
                                  : std::string("plain"))
          << "\nf";
      for (size_t c = 0; c < polygon.corners.size(); ++c)
        obj << ' ' << vertices + c + 1 << '/' << vertices + c + 1;
      obj << '\n';
      vertices += static_cast<uint32_t>(polygon.corners.size());
    }
    std::ofstream(dir_ / "scene.obj") << obj.str();
    return dir_ / "scene.obj";
  }

  // Runs retexture and build; checks every face's texels against its source image.
  void expectTexelsFollowTheFaces(const std::string& method) {
    const std::filesystem::path objPath = writeScene(), out = dir_ / ("out-" + method);
    const auto retextured = vt(
        {"retexture", objPath.string(), "-o", out.string(), "--no-coherence", "--method", method});
    ASSERT_EQ(retextured.exitCode, 0) << retextured.err;
    EXPECT_THAT(retextured.out, HasSubstr("retextured scene: "));
    EXPECT_THAT(retextured.err, AllOf(HasSubstr("warning: scene: "), HasSubstr("plain")));
    const auto report = nlohmann::json::parse(test::slurp(out / "scene.report.json"));
    EXPECT_EQ(report["chosen_method"], method);
    const auto layoutJson = nlohmann::json::parse(test::slurp(out / "scene.layout.json"));

    const auto built = vt({"build", (out / "scene.layout.json").string(), "-o",
                           (dir_ / (method + ".vt")).string(), "-q"});
    ASSERT_EQ(built.exitCode, 0) << built.err;
    const VirtualTextureReader reader(dir_ / (method + ".vt"));
    const LevelImage finest = assembleLevel(reader, reader.description().finestLevel());
    ASSERT_EQ(finest.channels, 3u);
    ASSERT_EQ(uint64_t{finest.side}, layoutJson["side"].get<uint64_t>());

    // The scene as the command read it: its vertices are the written mesh's, in order.
    const TexturedScene scene = loadObjScene(objPath, dir_ / "images");
    std::vector<glm::dvec2> newUvs;
    std::vector<uint32_t> indices;
    uint32_t groups = 0;
    std::istringstream mesh(test::slurp(out / "scene.obj"));
    for (std::string line; std::getline(mesh, line);) {
      std::istringstream words(line);
      std::string keyword;
      words >> keyword;
      if (keyword == "vt") {
        double u = 0.0, v = 0.0;
        words >> u >> v;
        newUvs.emplace_back(u, 1.0 - v);  // OBJ stores v = 1 - t
      } else if (keyword == "f") {
        for (std::string corner; words >> corner;)
          indices.push_back(static_cast<uint32_t>(std::stoul(corner)) - 1);
      } else if (keyword == "g") {
        ++groups;
      }
    }
    ASSERT_EQ(newUvs.size(), scene.uvs.size());
    ASSERT_EQ(indices, scene.indices);
    EXPECT_EQ(groups, scene.faces.size());

    std::mt19937 rng(3);
    const double side = finest.side;
    uint64_t checked = 0;
    for (size_t f = 0; f < scene.faces.size(); ++f) {
      const TexturedFace& face = scene.faces[f];
      const SourceTexture& texture = scene.textures[face.texture];
      const RgbImage& image = images_.at(texture.file.filename().string());
      ASSERT_EQ(image.width, texture.width);
      for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3)
        for (int k = 0; k < 8; ++k) {
          double b1 = uniform(rng, 0.0, 1.0), b2 = uniform(rng, 0.0, 1.0);
          if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
          const double b[3] = {1.0 - b1 - b2, b1, b2};
          glm::dvec2 st(0.0), newSt(0.0);
          for (int c = 0; c < 3; ++c) {
            st += b[c] * glm::dvec2(scene.uvs[scene.indices[t + c]]);
            newSt += b[c] * newUvs[scene.indices[t + c]];
          }
          const double u = st.x * texture.width, v = st.y * texture.height;
          if (nearTexelBoundary(u) || nearTexelBoundary(v)) continue;
          const int64_t sx = floorMod(static_cast<int64_t>(std::floor(u)), texture.width);
          const int64_t sy = floorMod(static_cast<int64_t>(std::floor(v)), texture.height);
          const auto X = static_cast<int64_t>(std::floor(newSt.x * side));
          const auto Y = static_cast<int64_t>(std::floor(newSt.y * side));
          ASSERT_TRUE(X >= 0 && Y >= 0 && X < int64_t{finest.side} && Y < int64_t{finest.side});
          for (uint32_t c = 0; c < 3; ++c) {
            const int expected = image.texels[(size_t(sy) * image.width + size_t(sx)) * 3 + c];
            const int actual =
                std::to_integer<int>(finest.texels[(size_t(Y) * finest.side + size_t(X)) * 3 + c]);
            ASSERT_EQ(actual, expected)
                << "face " << f << " (" << texture.name << ") source texel (" << sx << ", " << sy
                << ") at virtual texel (" << X << ", " << Y << ") channel " << c;
          }
          ++checked;
        }
    }
    EXPECT_GT(checked, 6 * scene.indices.size() / 3);  // most of 8 points per triangle
  }

  test::ScratchDirectory dir_;
  std::map<std::string, RgbImage> images_;
};

TEST_F(RetextureOutputs, ChartsBuildToTheSourceTexels) { expectTexelsFollowTheFaces("charts"); }

TEST_F(RetextureOutputs, BaselineBuildsToTheSourceTexels) {
  expectTexelsFollowTheFaces("baseline");
}

TEST_F(RetextureOutputs, MissingObjIsRejectedNamingIt) {
  const auto result =
      vt({"retexture", (dir_ / "absent.obj").string(), "-o", (dir_ / "out").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_THAT(result.err, AllOf(HasSubstr("absent.obj"), HasSubstr("not found")));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out" / "absent.layout.json"));
}

}  // namespace
}  // namespace vt
