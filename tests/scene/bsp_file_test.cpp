#include "scene/bsp_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "scene/bezier_patch.h"
#include "scene/bsp_entities.h"
#include "scene/quake3_fixtures.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

using test::appendI32;
using test::BspBuilder;
using test::bspVertex;
using test::kIndicesLump;
using test::kLumps;
using test::kShadersLump;
using test::kSurfacesLump;
using test::kVerticesLump;
using test::lumpLengthAt;
using test::lumpOffsetAt;
using test::putI32;

// A map with one surface of each kind: a quad polygon, a 3x3 patch, a two-triangle mesh, a flare
// and a surface of an unknown type.
BspBuilder validMap() {
  BspBuilder map;
  map.entities = "{\n\"classname\" \"worldspawn\"\n}\n";
  map.shaders = {{"textures/base_wall/concrete", 0, 1},
                 {"textures/skies/blue", kSurfaceSky | kSurfaceNoDraw, 0},
                 {std::string(64, 'x'), 0, kContentsFog}};  // a name filling all 64 bytes
  map.vertices = {bspVertex({0, 0, 0}, {0, 0}), bspVertex({64, 0, 0}, {1, 0}),
                  bspVertex({64, 64, 0}, {1, 1}), bspVertex({0, 64, 0}, {0, 1})};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      map.vertices.push_back(
          bspVertex({32.0f * i, 32.0f * j, i == 1 && j == 1 ? 16.0f : 0.0f}, {0.5f * i, 0.5f * j}));
  map.vertices.push_back(bspVertex({1.5f, -2.25f, 1e6f}, {-3.0f, 7.5f}));
  map.vertices.push_back(bspVertex({2, 0, 0}, {0, 0}));
  map.vertices.push_back(bspVertex({2, 1, 0}, {0, 0}));
  map.indices = {0, 1, 2, 0, 2, 3, 0, 1, 2, 2, 1, 0};
  BspSurface polygon;
  polygon.shader = 0;
  polygon.type = static_cast<int32_t>(BspSurfaceType::kPolygon);
  polygon.firstVertex = 0, polygon.vertexCount = 4;
  polygon.firstIndex = 0, polygon.indexCount = 6;
  polygon.normal = {0, 0, 1};
  BspSurface patch;
  patch.shader = 1;
  patch.fog = 0;
  patch.type = static_cast<int32_t>(BspSurfaceType::kPatch);
  patch.firstVertex = 4, patch.vertexCount = 9;
  patch.patchWidth = 3, patch.patchHeight = 3;
  BspSurface mesh;
  mesh.shader = 2;
  mesh.type = static_cast<int32_t>(BspSurfaceType::kMesh);
  mesh.firstVertex = 13, mesh.vertexCount = 3;
  mesh.firstIndex = 6, mesh.indexCount = 6;
  BspSurface flare;
  flare.type = static_cast<int32_t>(BspSurfaceType::kFlare);
  flare.firstVertex = 12345;  // no vertices: the range is not used, so not checked
  BspSurface unknown;
  unknown.type = 9;
  map.surfaces = {polygon, patch, mesh, flare, unknown};
  return map;
}

const std::string kName = "pak0.pk3:maps/test.bsp";

// The map is rejected with an InputError naming the file and containing `problem`.
void expectRejected(const std::vector<uint8_t>& bytes, const std::string& problem) {
  EXPECT_THAT([&] { parseBsp(bytes, kName); },
              ThrowsMessage<InputError>(AllOf(StartsWith(kName + ": "), HasSubstr(problem))));
}
void expectRejected(const BspBuilder& map, const std::string& problem) {
  expectRejected(map.build(), problem);
}

TEST(BspFile, ParsesEveryLumpExactly) {
  const BspFile bsp = parseBsp(validMap().build(), kName);
  EXPECT_EQ(bsp.entities, "{\n\"classname\" \"worldspawn\"\n}\n");  // the NUL stripped
  ASSERT_EQ(bsp.shaders.size(), 3u);
  EXPECT_EQ(bsp.shaders[0].name, "textures/base_wall/concrete");
  EXPECT_EQ(bsp.shaders[0].contentFlags, 1);
  EXPECT_EQ(bsp.shaders[1].name, "textures/skies/blue");
  EXPECT_EQ(bsp.shaders[1].surfaceFlags, kSurfaceSky | kSurfaceNoDraw);
  EXPECT_EQ(bsp.shaders[2].name, std::string(64, 'x'));
  EXPECT_EQ(bsp.shaders[2].contentFlags, kContentsFog);

  ASSERT_EQ(bsp.vertices.size(), 16u);
  EXPECT_EQ(bsp.vertices[2].position, glm::vec3(64, 64, 0));
  EXPECT_EQ(bsp.vertices[8].position, glm::vec3(32, 32, 16));
  EXPECT_EQ(bsp.vertices[13].position, glm::vec3(1.5f, -2.25f, 1e6f));
  EXPECT_EQ(bsp.vertices[13].st, glm::vec2(-3.0f, 7.5f));  // not the lightmap coordinates
  EXPECT_EQ(bsp.vertices[13].normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(bsp.indices, (std::vector<int32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 2, 1, 0}));

  ASSERT_EQ(bsp.surfaces.size(), 5u);
  const BspSurface& polygon = bsp.surfaces[0];
  EXPECT_EQ(polygon.type, 1);
  EXPECT_EQ(polygon.shader, 0);
  EXPECT_EQ(polygon.fog, -1);
  EXPECT_EQ(polygon.vertexCount, 4);
  EXPECT_EQ(polygon.indexCount, 6);
  EXPECT_EQ(polygon.normal, glm::vec3(0, 0, 1));  // the third lightmap vector
  const BspSurface& patch = bsp.surfaces[1];
  EXPECT_EQ(patch.type, 2);
  EXPECT_EQ(patch.fog, 0);
  EXPECT_EQ(patch.firstVertex, 4);
  EXPECT_EQ(patch.patchWidth, 3);
  EXPECT_EQ(patch.patchHeight, 3);
  EXPECT_EQ(bsp.surfaces[2].firstIndex, 6);
  EXPECT_EQ(bsp.surfaces[3].type, 4);
  EXPECT_EQ(bsp.surfaces[3].firstVertex, 12345);  // kept: the scene counts and skips flares
  EXPECT_EQ(bsp.surfaces[4].type, 9);
}

TEST(BspFile, KeepsNonFiniteFloats) {
  // The scene skips surfaces with non-finite vertices and counts them; parsing keeps them.
  BspBuilder map = validMap();
  map.vertices[0].position.x = std::numeric_limits<float>::infinity();
  map.vertices[1].st.y = std::numeric_limits<float>::quiet_NaN();
  const BspFile bsp = parseBsp(map.build(), kName);
  EXPECT_TRUE(std::isinf(bsp.vertices[0].position.x));
  EXPECT_TRUE(std::isnan(bsp.vertices[1].st.y));
}

TEST(BspFile, RejectsABadHeader) {
  const std::vector<uint8_t> valid = validMap().build();
  std::vector<uint8_t> bytes = valid;
  bytes[0] = 'V';
  expectRejected(bytes, "header: bad magic 'VBSP', expected 'IBSP'");
  bytes = valid;
  putI32(bytes, 4, 47);
  expectRejected(bytes, "header: version 47 is not 46");
  bytes.assign(valid.begin(), valid.begin() + 100);
  expectRejected(bytes, "header: truncated: the file has 100 bytes, the header needs 144");
  expectRejected(std::vector<uint8_t>{}, "header: truncated: the file has 0 bytes");
}

TEST(BspFile, RejectsLumpsOutsideTheFile) {
  const std::vector<uint8_t> valid = validMap().build();
  std::vector<uint8_t> bytes = valid;
  putI32(bytes, lumpOffsetAt(kVerticesLump), static_cast<int32_t>(bytes.size()) - 44);
  expectRejected(bytes, "lump drawverts: offset");
  expectRejected(bytes, "is past the end of the " + std::to_string(bytes.size()) + "-byte file");
  bytes = valid;
  putI32(bytes, lumpLengthAt(kSurfacesLump), 1 << 30);
  expectRejected(bytes, "lump surfaces: offset");
  bytes = valid;
  putI32(bytes, lumpOffsetAt(kShadersLump), std::numeric_limits<int32_t>::max());
  expectRejected(bytes, "lump shaders: offset 2147483647");
  bytes = valid;
  putI32(bytes, lumpLengthAt(kIndicesLump), -4);
  expectRejected(bytes, "lump drawindexes: negative length -4");
  // The last lump in the file loses its end: a truncated file.
  bytes.assign(valid.begin(), valid.end() - 1);
  expectRejected(bytes, "is past the end of the " + std::to_string(bytes.size()) + "-byte file");
}

TEST(BspFile, RejectsLumpsOfPartialRecords) {
  const std::vector<uint8_t> valid = validMap().build();
  const std::pair<int, std::string> cases[] = {
      {kShadersLump, "lump shaders: length 215 is not a multiple of the 72-byte record"},
      {kVerticesLump, "lump drawverts: length 703 is not a multiple of the 44-byte record"},
      {kIndicesLump, "lump drawindexes: length 47 is not a multiple of the 4-byte record"},
      {kSurfacesLump, "lump surfaces: length 519 is not a multiple of the 104-byte record"}};
  for (const auto& [lump, problem] : cases) {
    std::vector<uint8_t> bytes = valid;
    const size_t at = lumpLengthAt(lump);
    putI32(bytes, at, static_cast<int32_t>(bytes[at] | bytes[at + 1] << 8) - 1);
    expectRejected(bytes, problem);
  }
}

TEST(BspFile, RejectsSurfacesOutsideTheirLumps) {
  BspBuilder map = validMap();
  map.surfaces[0].vertexCount = 17;
  expectRejected(map,
                 "surface 0: vertex range [0, 17) is outside the 16 records of lump drawverts");
  map = validMap();
  map.surfaces[1].firstVertex = -1;
  expectRejected(map, "surface 1: vertex range [-1, 8) is outside");
  map = validMap();
  map.surfaces[2].firstVertex = std::numeric_limits<int32_t>::max();  // no 32-bit overflow
  expectRejected(map, "surface 2: vertex range [2147483647, 2147483650) is outside");
  map = validMap();
  map.surfaces[3].vertexCount = 1;  // a flare that claims vertices must have them
  expectRejected(map, "surface 3: vertex range [12345, 12346) is outside");
  map = validMap();
  map.surfaces[2].indexCount = 9;
  expectRejected(map,
                 "surface 2: index range [6, 15) is outside the 12 records of lump drawindexes");
  map = validMap();
  map.surfaces[0].indexCount = -3;
  expectRejected(map, "surface 0: index range [0, -3) is outside");
}

TEST(BspFile, RejectsBadTriangles) {
  BspBuilder map = validMap();
  map.indices[4] = 4;  // the quad has vertices 0..3
  expectRejected(map,
                 "surface 0: index 4 (drawindexes record 4) is outside the surface's 4 vertices");
  map = validMap();
  map.indices[9] = -1;
  expectRejected(map, "surface 2: index -1 (drawindexes record 9) is outside");
  map = validMap();
  map.surfaces[0].indexCount = 5;
  expectRejected(map, "surface 0: index count 5 is not a multiple of 3");
}

TEST(BspFile, RejectsShaderNumbersOutOfRange) {
  BspBuilder map = validMap();
  map.surfaces[1].shader = 3;
  expectRejected(map, "surface 1: shader number 3 is outside the 3 shaders");
  map = validMap();
  map.surfaces[4].shader = -1;
  expectRejected(map, "surface 4: shader number -1 is outside the 3 shaders");
}

TEST(BspFile, RejectsPatchGridsThatAreNotOdd) {
  BspBuilder map = validMap();
  map.surfaces[1].patchWidth = 4;
  expectRejected(map, "surface 1: patch width 4 is even");
  map = validMap();
  map.surfaces[1].patchHeight = 1;
  expectRejected(map, "surface 1: patch height 1 is less than 3");
  map = validMap();
  map.surfaces[1].patchWidth = 5;
  expectRejected(map, "surface 1: patch size 5 x 3 does not match its 9 vertices");
  map = validMap();
  map.surfaces[1].patchWidth = 65537, map.surfaces[1].patchHeight = 65537;  // w * h overflows
  expectRejected(map, "surface 1: patch size 65537 x 65537 does not match its 9 vertices");
}

// ---------------------------------------------------------------------------------------------
// Patch tessellation.

struct ControlGrid {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> st;
};

// Control points f(i, j) at column i and row j of a width x height grid, st = (i, j) / 4.
template <typename F>
ControlGrid controlGrid(int width, int height, F f) {
  ControlGrid grid;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      grid.positions.push_back(f(i, j));
      grid.st.push_back(glm::vec2(i, j) / 4.0f);
    }
  return grid;
}

TessellatedPatch tessellate(const ControlGrid& grid, int width, int height, int level) {
  return tessellatePatch(grid.positions, grid.st, width, height, level);
}

TEST(BezierPatch, FlatPatchStaysOnItsControlPlane) {
  // Irregular control points in the plane z = 0: every vertex has z = 0 exactly.
  const ControlGrid wavy = controlGrid(5, 3, [](int i, int j) {
    return glm::vec3(10.0f * i + 3.7f * std::sin(float(j + 2 * i)), 7.0f * j + 1.3f * i * i, 0);
  });
  const TessellatedPatch flat = tessellate(wavy, 5, 3, 7);
  for (const glm::vec3& p : flat.positions) EXPECT_EQ(p.z, 0.0f);
  // Evenly spaced control points on a tilted plane: the surface is that plane, linearly
  // parametrized, and with a power-of-two level every vertex is exact in floating point.
  const ControlGrid even = controlGrid(5, 3, [](int i, int j) {
    return glm::vec3(16.0f * i, 8.0f * j, 2.0f * i - 3.0f * j + 5.0f);
  });
  const int level = 8;
  const TessellatedPatch tilted = tessellate(even, 5, 3, level);
  ASSERT_EQ(tilted.positions.size(), size_t{17 * 9});
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 17; ++c) {
      const float i = float(c) * 2 / level, j = float(r) * 2 / level;  // control-grid coordinates
      EXPECT_EQ(tilted.positions[r * 17 + c], glm::vec3(16 * i, 8 * j, 2 * i - 3 * j + 5));
      EXPECT_EQ(tilted.st[r * 17 + c], glm::vec2(i, j) / 4.0f);
    }
}

TEST(BezierPatch, CornersAreTheControlPoints) {
  // A curved 5x5 grid: the corners of each of its 2x2 patches are control points, bit for bit,
  // at any level.
  const ControlGrid curved = controlGrid(5, 5, [](int i, int j) {
    return glm::vec3(0.1f * i + std::cos(0.7f * j), 0.3f * j * j, std::sin(1.1f * i + 0.3f * j));
  });
  for (const int level : {1, 3, 8}) {
    const TessellatedPatch patch = tessellate(curved, 5, 5, level);
    const int columns = 2 * level + 1;
    ASSERT_EQ(patch.positions.size(), size_t(columns * columns));
    for (int j = 0; j <= 4; j += 2)
      for (int i = 0; i <= 4; i += 2) {
        const size_t v = size_t(j / 2 * level * columns + i / 2 * level);
        EXPECT_EQ(patch.positions[v], curved.positions[j * 5 + i]) << level << " " << i << " " << j;
        EXPECT_EQ(patch.st[v], curved.st[j * 5 + i]);
      }
  }
}

TEST(BezierPatch, FiveByThreeGridSharesItsMiddleEdge) {
  const auto f = [](int i, int j) {
    return glm::vec3(10.0f * i + std::sin(0.9f * i * j), 6.0f * j, std::cos(1.7f * i + j));
  };
  const ControlGrid whole = controlGrid(5, 3, f);
  const TessellatedPatch patch = tessellate(whole, 5, 3, 4);
  ASSERT_EQ(patch.positions.size(), size_t{9 * 5});
  ASSERT_EQ(patch.st.size(), size_t{9 * 5});
  ASSERT_EQ(patch.indices.size(), size_t{8 * 4 * 6});
  // Each half tessellated alone gives the same vertices; the middle column, shared by both
  // halves, is exactly the same in the left's last column and the right's first.
  const ControlGrid left = controlGrid(3, 3, f);
  const ControlGrid right = controlGrid(3, 3, [&](int i, int j) { return f(i + 2, j); });
  const TessellatedPatch leftPatch = tessellate(left, 3, 3, 4);
  const TessellatedPatch rightPatch = tessellate(right, 3, 3, 4);
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) {
      EXPECT_EQ(patch.positions[r * 9 + c], leftPatch.positions[r * 5 + c]) << r << " " << c;
      EXPECT_EQ(patch.positions[r * 9 + 4 + c], rightPatch.positions[r * 5 + c]) << r << " " << c;
    }
  // The shared edge is the quadratic Bezier curve of control column 2 alone.
  for (int r = 0; r < 5; ++r) {
    const double t = r / 4.0;
    const glm::dvec3 edge = (1 - t) * (1 - t) * glm::dvec3(f(2, 0)) +
                            2 * t * (1 - t) * glm::dvec3(f(2, 1)) + t * t * glm::dvec3(f(2, 2));
    EXPECT_EQ(patch.positions[r * 9 + 4], glm::vec3(edge));
  }
}

TEST(BezierPatch, CurvedPointIsTheBernsteinCombination) {
  // Heights z_ij over a unit grid; st = (i, j) / 4 evaluates with the same weights.
  const float z[3][3] = {{0, 1, 0}, {2, 8, 2}, {0, 1, 0}};
  const ControlGrid grid =
      controlGrid(3, 3, [&](int i, int j) { return glm::vec3(i, j, z[j][i]); });
  // Centre, u = v = 1/2: weights 1/16 at corners, 1/8 on edges, 1/4 at the centre:
  // z = (1 + 2 + 2 + 1) / 8 + 8 / 4 = 2.75.
  const TessellatedPatch two = tessellate(grid, 3, 3, 2);
  EXPECT_EQ(two.positions[4], glm::vec3(1, 1, 2.75f));
  EXPECT_EQ(two.st[4], glm::vec2(0.25f, 0.25f));
  // u = 1/4, v = 1/2 (level 4, column 1, row 2): column weights (9, 6, 1) / 16, row weights
  // (1, 2, 1) / 4: rows give 6/16, 68/16, 6/16, so z = (6 + 2 * 68 + 6) / 64 = 37/16; x = 1/2.
  const TessellatedPatch four = tessellate(grid, 3, 3, 4);
  EXPECT_EQ(four.positions[2 * 5 + 1], glm::vec3(0.5f, 1, 37.0f / 16));
  EXPECT_EQ(four.st[2 * 5 + 1], glm::vec2(0.125f, 0.25f));
}

TEST(BezierPatch, TrianglesCoverTheGridWithOneWinding) {
  const ControlGrid bumpy = controlGrid(5, 7, [](int i, int j) {
    return glm::vec3(8.0f * i, 8.0f * j, 3.0f * std::sin(float(i * j)));
  });
  const TessellatedPatch patch = tessellate(bumpy, 5, 7, 5);
  const size_t columns = 11, rows = 16;
  ASSERT_EQ(patch.positions.size(), columns * rows);
  ASSERT_EQ(patch.indices.size(), (columns - 1) * (rows - 1) * 6);
  // Seen from +z every triangle turns the same way (Quake 3's order: clockwise in a right-handed
  // x-right, y-up view, as the rows run to +y).
  for (size_t t = 0; t < patch.indices.size(); t += 3) {
    ASSERT_LT(patch.indices[t + 0], patch.positions.size());
    ASSERT_LT(patch.indices[t + 1], patch.positions.size());
    ASSERT_LT(patch.indices[t + 2], patch.positions.size());
    const glm::vec3 a = patch.positions[patch.indices[t]],
                    b = patch.positions[patch.indices[t + 1]],
                    c = patch.positions[patch.indices[t + 2]];
    EXPECT_LT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3;
  }
}

TEST(BezierPatch, RejectsBadArguments) {
  const ControlGrid grid = controlGrid(3, 3, [](int i, int j) { return glm::vec3(i, j, 0); });
  // Each refusal names what was wrong with the patch the map stores, or with the level.
  using Refusal = std::invalid_argument;
  EXPECT_THAT([&] { tessellate(grid, 3, 3, 0); },
              ThrowsMessage<Refusal>("patch tessellation level must be at least 1"));
  EXPECT_THAT([&] { tessellatePatch(grid.positions, grid.st, 2, 4, 4); },
              ThrowsMessage<Refusal>(HasSubstr("patch control grid 2 x 4 is not (2n+1) x (2m+1)")));
  EXPECT_THAT([&] { tessellatePatch(grid.positions, grid.st, 1, 9, 4); },
              ThrowsMessage<Refusal>(HasSubstr("patch control grid 1 x 9 is not (2n+1) x (2m+1)")));
  EXPECT_THAT([&] { tessellatePatch(grid.positions, grid.st, 3, 5, 4); },
              ThrowsMessage<Refusal>("patch has 9 positions and 9 st for 15 control points"));
  EXPECT_THAT([&] { tessellatePatch(grid.positions, std::span(grid.st).first(8), 3, 3, 4); },
              ThrowsMessage<Refusal>("patch has 9 positions and 8 st for 9 control points"));
}

// ---------------------------------------------------------------------------------------------
// The entity lump.

TEST(BspEntities, ParsesKeysAndValues) {
  const std::string text =
      "{\n"
      "\"classname\" \"worldspawn\"\n"
      "\"message\" \"Test map // with slashes\"\n"
      "}\n"
      "// a comment between entities\n"
      "{\n"
      "\"origin\" \"-64 128 24\"\n"
      "\"classname\" \"info_player_deathmatch\"\n"
      "\"angle\" \"90\"\n"
      "}\n"
      "{ \"classname\" \"light\" \"light\" \"\" }";
  const std::vector<BspEntity> entities = parseEntities(text, kName);
  ASSERT_EQ(entities.size(), 3u);
  EXPECT_EQ(entities[0].at("classname"), "worldspawn");
  EXPECT_EQ(entities[0].at("message"), "Test map // with slashes");
  EXPECT_EQ(entities[1], (BspEntity{{"classname", "info_player_deathmatch"},
                                    {"origin", "-64 128 24"},
                                    {"angle", "90"}}));
  EXPECT_EQ(entities[2].at("light"), "");
  EXPECT_TRUE(parseEntities("", kName).empty());
}

TEST(BspEntities, RejectsMalformedTextNamingTheLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"{\n\"classname\" \"worldspawn\"\n",
       "entities line 1: the entity opened here is never closed"},
      {"{\n\"classname\" \"worldspawn\"\n}\n}\n", "entities line 4: '}' without a matching '{'"},
      {"{\n\"classname\" \"world\nspawn\"\n\"message\" \"open\n}\n",
       "entities line 4: unterminated string"},
      {"{\n\"classname\" \"light\"\n\"origin\"\n}\n",
       "entities line 4: key \"origin\" has no value"},
      {"{\n\"classname\" \"light\"\n{\n}\n", "entities line 3: '{' inside an entity"},
      {"\"classname\" \"light\"\n", "entities line 1: string \"classname\" outside an entity"},
      {"{\nclassname light\n}\n", "entities line 2: unexpected character 'c' outside a string"}};
  for (const auto& [text, problem] : cases)
    EXPECT_THAT([&entities = text] { parseEntities(entities, kName); },
                ThrowsMessage<InputError>(AllOf(StartsWith(kName + ": "), HasSubstr(problem))))
        << text;
}

}  // namespace
}  // namespace vt
