// A Quake 3 map read from a generated .pk3: which surfaces become faces, which are skipped and
// counted, how textures are found, the axes, the winding, the spawn viewpoints, and bad input.

#include "scene/quake3_scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/error.h"
#include "common/image_file.h"
#include "scene/quake3_fixtures.h"
#include "scene/quake_axes.h"
#include "test_support.h"

namespace vt {
namespace {

using test::bspVertex;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

BspSurface surface(int32_t shader, BspSurfaceType type, int32_t firstVertex, int32_t vertexCount,
                   int32_t firstIndex = 0, int32_t indexCount = 0) {
  BspSurface s;
  s.shader = shader;
  s.type = static_cast<int32_t>(type);
  s.firstVertex = firstVertex, s.vertexCount = vertexCount;
  s.firstIndex = firstIndex, s.indexCount = indexCount;
  return s;
}

class Quake3Scene : public ::testing::Test {
 protected:
  // An image file's bytes: a PNG of `width` x `height` texels, written and read back.
  std::string imageBytes(uint32_t width, uint32_t height) {
    const std::filesystem::path file = scratch_ / "image.png";
    writeImage8(file, width, height, 3, std::vector<std::byte>(width * height * 3, std::byte{7}));
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // Shaders: 0 wall (an image), 1 sky, 2 nodraw, 3 fog, 4 only a script defines it, 5 missing.
  test::BspBuilder map() {
    test::BspBuilder map;
    map.entities =
        "{\n\"classname\" \"worldspawn\"\n}\n"
        "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"100 200 30\"\n"
        "\"angle\" \"90\"\n}\n";
    map.shaders = {{"textures/base/wall", 0, 1},
                   {"textures/skies/sky", kSurfaceSky, 0},
                   {"textures/common/nodraw", kSurfaceNoDraw, 0},
                   {"textures/fog/fog", 0, kContentsFog},
                   {"textures/sfx/glow", 0, 1},
                   {"textures/base/gone", 0, 1}};
    // 0-3: a quad in the z = 0 plane, wound clockwise seen from +z (its normals' side).
    map.vertices = {bspVertex({0, 0, 0}, {0, 0}), bspVertex({0, 64, 0}, {0, 1}),
                    bspVertex({64, 64, 0}, {1, 1}), bspVertex({64, 0, 0}, {1, 0})};
    map.indices = {0, 1, 2, 0, 2, 3};
    // 4-9: a mesh of two triangles that share no vertex.
    for (const float x : {200.0f, 300.0f})
      for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(16, 0, 0), glm::vec3(0, 16, 0)})
        map.vertices.push_back(bspVertex(p + glm::vec3(x, 0, 0), glm::vec2(p) / 16.0f));
    map.indices.insert(map.indices.end(), {0, 1, 2, 3, 4, 5});
    // 10-18: a 3x3 patch.
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        map.vertices.push_back(
            bspVertex({32.0f * i, 32.0f * j, 100.0f}, {0.5f * i, 0.5f * j}, {0, 0, 1}));
    // 19-21: a triangle with a NaN coordinate.
    map.vertices.push_back(bspVertex({0, 0, NAN}, {0, 0}));
    map.vertices.push_back(bspVertex({1, 0, 0}, {0, 0}));
    map.vertices.push_back(bspVertex({0, 1, 0}, {0, 0}));
    map.indices.insert(map.indices.end(), {0, 1, 2});
    BspSurface patch = surface(0, BspSurfaceType::kPatch, 10, 9);
    patch.patchWidth = patch.patchHeight = 3;
    map.surfaces = {surface(0, BspSurfaceType::kPolygon, 0, 4, 0, 6),
                    surface(4, BspSurfaceType::kMesh, 4, 6, 6, 6),
                    patch,
                    surface(1, BspSurfaceType::kPolygon, 0, 4, 0, 6),
                    surface(2, BspSurfaceType::kPolygon, 0, 4, 0, 6),
                    surface(3, BspSurfaceType::kPolygon, 0, 4, 0, 6),
                    surface(5, BspSurfaceType::kPolygon, 0, 4, 0, 6),
                    surface(0, BspSurfaceType::kFlare, 0, 0),
                    surface(0, BspSurfaceType::kPolygon, 19, 3, 12, 3)};
    return map;
  }

  void writePackage(const test::BspBuilder& bsp) {
    const std::vector<uint8_t> bytes = bsp.build();
    test::writeZip(scratch_ / "baseoa/pak0.pk3",
                   {{"maps/test.bsp", std::string(bytes.begin(), bytes.end())},
                    {"textures/base/Wall.jpg", imageBytes(32, 16)},
                    {"textures/sfx/glow_blue.tga", imageBytes(8, 8)},
                    {"scripts/sfx.shader",
                     "textures/sfx/glow\n{\n { map $lightmap }\n"
                     " { map textures/sfx/glow_blue.tga }\n}\n"}});
  }

  TexturedScene load() {
    return loadQuake3Map(PackageFiles::fromFolders({scratch_ / "baseoa"}), "test",
                         scratch_ / "images");
  }

  void SetUp() override { std::filesystem::create_directories(scratch_ / "baseoa"); }

  test::ScratchDirectory scratch_;
};

TEST_F(Quake3Scene, DrawsPolygonsMeshPiecesAndPatchesAndCountsWhatItSkips) {
  writePackage(map());
  const TexturedScene scene = load();
  // The quad, the mesh's two unconnected triangles (one face each), the patch, the missing
  // texture's quad.
  ASSERT_EQ(scene.faces.size(), 5u);
  EXPECT_EQ(scene.faces[0].indexCount, 6u);
  EXPECT_EQ(scene.faces[1].indexCount, 3u);
  EXPECT_EQ(scene.faces[2].indexCount, 3u);
  const int level = kPatchTessellationLevel;
  EXPECT_EQ(scene.faces[3].indexCount, static_cast<uint32_t>(6 * level * level));
  EXPECT_EQ(scene.patchFaces, 1u);
  EXPECT_EQ(scene.splitSurfaces, 1u);
  EXPECT_EQ(scene.skipped.sky, 1u);
  EXPECT_EQ(scene.skipped.noDraw, 1u);
  EXPECT_EQ(scene.skipped.fog, 1u);
  EXPECT_EQ(scene.skipped.flare, 1u);
  EXPECT_EQ(scene.skipped.notFinite, 1u);
  EXPECT_EQ(scene.skipped.total(), 5u);
}

TEST_F(Quake3Scene, FindsImagesByNameAndThroughScriptsAndDrawsTheMissingAsACheckerWithAWarning) {
  writePackage(map());
  const TexturedScene scene = load();
  ASSERT_EQ(scene.textures.size(), 3u);
  EXPECT_EQ(scene.textures[0].name, "textures/base/wall");
  EXPECT_EQ(scene.textures[0].width, 32u);  // Wall.jpg, whatever the case
  EXPECT_EQ(scene.textures[0].height, 16u);
  EXPECT_THAT(scene.textures[0].foundAs, HasSubstr("textures/base/Wall.jpg (image)"));
  EXPECT_TRUE(std::filesystem::exists(scene.textures[0].file));
  EXPECT_EQ(scene.textures[1].width, 8u);  // the script's stage image
  EXPECT_THAT(scene.textures[1].foundAs, HasSubstr("(shader stage)"));
  EXPECT_TRUE(scene.textures[2].missing);
  EXPECT_EQ(scene.textures[2].width, 64u);
  EXPECT_EQ(scene.textures[2].file.filename(), "missing_texture.png");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_THAT(scene.warnings[0], HasSubstr("textures/base/gone"));
}

TEST_F(Quake3Scene, ConvertsAxesWindsCounterClockwiseAndStandsAtTheSpawnPoint) {
  writePackage(map());
  const TexturedScene scene = load();
  // Quake (x, y, z) -> (x, z, -y) in metres.
  EXPECT_EQ(fromQuake({1, 2, 3}), glm::vec3(1, 3, -2) * kMetresPerQuakeUnit);
  // The quad faces +z in Quake, +y here: every triangle counter-clockwise seen from there.
  const TexturedFace& quad = scene.faces[0];
  for (uint32_t t = quad.firstIndex; t < quad.firstIndex + quad.indexCount; t += 3) {
    const glm::vec3 a = scene.positions[scene.indices[t]],
                    b = scene.positions[scene.indices[t + 1]],
                    c = scene.positions[scene.indices[t + 2]];
    EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f);
  }
  // Texture coordinates stay with their vertices: Quake's (x, y, 0) had st (x, y) / 64.
  for (uint32_t i = quad.firstIndex; i < quad.firstIndex + quad.indexCount; ++i) {
    const uint32_t v = scene.indices[i];
    EXPECT_EQ(scene.positions[v].y, 0.0f);
    EXPECT_NEAR(scene.uvs[v].x, scene.positions[v].x / (64.0f * kMetresPerQuakeUnit), 1e-6f);
    EXPECT_NEAR(scene.uvs[v].y, -scene.positions[v].z / (64.0f * kMetresPerQuakeUnit), 1e-6f);
  }
  ASSERT_EQ(scene.viewpoints.size(), 1u);
  const Camera& view = scene.viewpoints[0];
  EXPECT_EQ(view.position, fromQuake({100, 200, 30 + kQuakeViewHeight}));
  const glm::vec3 forward = glm::normalize(view.target - view.position);
  EXPECT_NEAR(forward.x, 0.0f, 1e-6f);  // angle 90: along Quake's +y, our -z
  EXPECT_NEAR(forward.z, -1.0f, 1e-6f);
}

TEST_F(Quake3Scene, RejectsAMissingMapATruncatedMapAndABrokenArchiveNamingThem) {
  writePackage(map());
  const PackageFiles files = PackageFiles::fromFolders({scratch_ / "baseoa"});
  EXPECT_THAT([&] { loadQuake3Map(files, "nothere", scratch_ / "images"); },
              ThrowsMessage<InputError>(HasSubstr("maps/nothere.bsp: no such map")));

  std::vector<uint8_t> bytes = map().build();
  bytes.resize(bytes.size() / 2);
  test::writeZip(scratch_ / "baseoa/pak1.pk3",
                 {{"maps/test.bsp", std::string(bytes.begin(), bytes.end())}});
  EXPECT_THAT([&] { load(); }, ThrowsMessage<InputError>(HasSubstr("pak1.pk3:maps/test.bsp")));

  std::ofstream(scratch_ / "baseoa/pak2.pk3") << "PK\x03\x04 not really a zip archive";
  EXPECT_THAT([&] { load(); }, ThrowsMessage<InputError>(HasSubstr("pak2.pk3")));
}

// An archive entry (found by the map's shader name, or by a shader stage) must not lead the
// extracted image out of the image folder, by name or through a symbolic link.
TEST_F(Quake3Scene, RefusesImageNamesThatLeaveTheImageFolderNamingArchiveAndEntry) {
  const auto writeWith = [&](const std::string& shader, const std::string& entry,
                             const std::string& script) {
    test::BspBuilder bsp = map();
    bsp.shaders[0].name = shader;
    std::filesystem::remove_all(scratch_ / "baseoa");
    std::filesystem::create_directories(scratch_ / "baseoa");
    const std::vector<uint8_t> bytes = bsp.build();
    test::writeZip(scratch_ / "baseoa/pak0.pk3",
                   {{"maps/test.bsp", std::string(bytes.begin(), bytes.end())},
                    {entry, imageBytes(4, 4)},
                    {"scripts/x.shader", script}});
  };
  const std::filesystem::path escaped = scratch_ / "escaped.tga";
  // By the shader's own name, "../escaped" from images/.
  writeWith("../escaped", "../escaped.tga", "");
  EXPECT_THAT(
      [&] { load(); },
      ThrowsMessage<InputError>(HasSubstr(
          "pak0.pk3:../escaped.tga: the name '../escaped.tga' leads outside the folder images/: it "
          "has a '..' component")));
  EXPECT_FALSE(std::filesystem::exists(escaped));
  // Through a shader stage naming it.
  writeWith("textures/base/stage", "textures/../../escaped.tga",
            "textures/base/stage\n{\n { map textures/../../escaped.tga }\n}\n");
  EXPECT_THAT([&] { load(); }, ThrowsMessage<InputError>(HasSubstr("it has a '..' component")));
  EXPECT_FALSE(std::filesystem::exists(escaped));
  // An absolute name.
  // (A shader name holds at most 63 characters.)
  const std::string absolute = "/tmp/vt-absolute-" + std::to_string(::getpid());
  writeWith(absolute, absolute + ".tga", "");
  EXPECT_THAT([&] { load(); }, ThrowsMessage<InputError>(HasSubstr("it is absolute")));
  EXPECT_FALSE(std::filesystem::exists(absolute + ".tga"));
  // A symbolic link inside the image folder leading out of it.
  writeWith("textures/base/wall", "textures/base/wall.tga", "");
  std::filesystem::create_directories(scratch_ / "images");
  std::filesystem::create_directories(scratch_ / "elsewhere");
  std::filesystem::create_directory_symlink(scratch_ / "elsewhere", scratch_ / "images/textures");
  EXPECT_THAT([&] { load(); },
              ThrowsMessage<InputError>(HasSubstr("images/textures is a symbolic link")));
  EXPECT_TRUE(std::filesystem::is_empty(scratch_ / "elsewhere"));
}

TEST_F(Quake3Scene, RejectsAMapThatDrawsNothing) {
  test::BspBuilder bsp = map();
  bsp.surfaces = {surface(1, BspSurfaceType::kPolygon, 0, 4, 0, 6)};  // only sky
  writePackage(bsp);
  EXPECT_THAT([&] { load(); }, ThrowsMessage<InputError>(HasSubstr("draws no faces")));
}

}  // namespace
}  // namespace vt
