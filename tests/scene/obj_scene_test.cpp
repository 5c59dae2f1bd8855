// OBJ scenes (obj_scene.h), the input of `vt retexture` besides Quake 3 maps: polygons become
// fan-triangulated faces, materials become source textures of the images' sizes, t = 1 - v, and
// broken input is rejected naming the file, or drawn as the checker with a warning.

#include "scene/obj_scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "common/error.h"
#include "common/image_file.h"
#include "scene/missing_texture.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

class ObjScene : public ::testing::Test {
 protected:
  void writeText(const std::string& name, const std::string& text) {
    std::filesystem::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
  }
  void writeImage(const std::string& name, uint32_t width, uint32_t height) {
    std::filesystem::create_directories((dir_ / name).parent_path());
    std::vector<std::byte> texels(size_t{width} * height * 3, std::byte{200});
    writeImage8(dir_ / name, width, height, 3, texels);
  }
  TexturedScene load(const std::string& name) { return loadObjScene(dir_ / name, dir_ / "images"); }
  // The message of the InputError loading `name` throws, or "" when it loads.
  std::string loadError(const std::string& name) {
    try {
      load(name);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  test::ScratchDirectory dir_;
};

// Three unit-square corners and a fourth, with texture coordinates for each.
const char* const kSquareVertices =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

TEST_F(ObjScene, PolygonsBecomeFanTriangulatedFacesWithTheirMaterialsTextures) {
  writeImage("brick.png", 32, 16);
  writeImage("maps/stone.png", 8, 24);
  writeText("scene.mtl",
            "newmtl brick\nKd 1 1 1\nmap_Kd brick.png\n"
            "newmtl stone\nmap_Kd maps/stone.png\n");
  writeText("scene.obj",
            "mtllib scene.mtl\n"
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 2 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.25\nvt -1.5 3\n"
            "usemtl brick\n"
            "f 1/1 2/2 3/3 4/4\n"  // a quad: one face of two triangles
            "usemtl stone\n"
            "f 1/1 2/2 5/5\n"
            "f 1/1 5/5 6/6 3/3 4/4\n"  // a pentagon: three triangles
            "usemtl brick\n"
            "f 2/2 5/5 6/6\n");
  const TexturedScene scene = load("scene.obj");
  EXPECT_EQ(scene.name, "scene");
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_EQ(scene.skipped.total(), 0u);

  ASSERT_EQ(scene.faces.size(), 4u);
  const uint32_t firstIndex[] = {0, 6, 9, 18}, indexCount[] = {6, 3, 9, 3},
                 texture[] = {0, 1, 1, 0};
  for (size_t f = 0; f < 4; ++f) {
    EXPECT_EQ(scene.faces[f].firstIndex, firstIndex[f]) << f;
    EXPECT_EQ(scene.faces[f].indexCount, indexCount[f]) << f;
    EXPECT_EQ(scene.faces[f].texture, texture[f]) << f;
  }
  // Each face owns its corners; fans from the first corner.
  ASSERT_EQ(scene.positions.size(), 4u + 3 + 5 + 3);
  ASSERT_EQ(scene.uvs.size(), scene.positions.size());
  EXPECT_EQ(scene.indices, (std::vector<uint32_t>{0,  1,  2, 0, 2, 3,              // quad
                                                  4,  5,  6,                       // triangle
                                                  7,  8,  9, 7, 9, 10, 7, 10, 11,  // pentagon
                                                  12, 13, 14}));
  EXPECT_EQ(scene.positions[9], glm::vec3(2.0f, 2.0f, 0.0f));
  // t = 1 - v, s unchanged (repetitions kept).
  EXPECT_EQ(scene.uvs[0], glm::vec2(0.0f, 1.0f));
  EXPECT_EQ(scene.uvs[2], glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(scene.uvs[6], glm::vec2(0.5f, 0.75f));
  EXPECT_EQ(scene.uvs[9], glm::vec2(-1.5f, -2.0f));

  ASSERT_EQ(scene.textures.size(), 2u);
  EXPECT_EQ(scene.textures[0].name, "brick");
  EXPECT_EQ(scene.textures[0].width, 32u);
  EXPECT_EQ(scene.textures[0].height, 16u);
  EXPECT_FALSE(scene.textures[0].missing);
  EXPECT_TRUE(std::filesystem::equivalent(scene.textures[0].file, dir_ / "brick.png"));
  EXPECT_EQ(scene.textures[1].name, "stone");
  EXPECT_EQ(scene.textures[1].width, 8u);
  EXPECT_EQ(scene.textures[1].height, 24u);
  EXPECT_FALSE(scene.textures[1].missing);
  EXPECT_TRUE(std::filesystem::equivalent(scene.textures[1].file, dir_ / "maps/stone.png"));
}

TEST_F(ObjScene, MissingObjIsAnErrorNamingIt) {
  EXPECT_THAT(loadError("absent.obj"), AllOf(HasSubstr("absent.obj"), HasSubstr("not found")));
}

TEST_F(ObjScene, MissingMaterialLibraryIsAnErrorNamingBoth) {
  writeText("scene.obj", std::string("mtllib nowhere.mtl\n") + kSquareVertices + "f 1/1 2/2 3/3\n");
  EXPECT_THAT(loadError("scene.obj"),
              AllOf(HasSubstr("scene.obj"), HasSubstr("nowhere.mtl"), HasSubstr("not found")));
}

TEST_F(ObjScene, FaceWithoutTextureCoordinatesIsAnError) {
  writeText("bare.obj", std::string(kSquareVertices) + "f 1/1 2/2 3/3\nf 1 3 4\n");
  EXPECT_THAT(loadError("bare.obj"),
              AllOf(HasSubstr("bare.obj"), HasSubstr("without texture coordinates")));
}

TEST_F(ObjScene, IndexOutOfRangeIsAnError) {
  writeText("far.obj", std::string(kSquareVertices) + "f 1/1 2/2 9/3\n");
  EXPECT_THAT(loadError("far.obj"), AllOf(HasSubstr("far.obj"), HasSubstr("index out of range")));
  writeText("fart.obj", std::string(kSquareVertices) + "f 1/1 2/2 3/5\n");
  EXPECT_THAT(loadError("fart.obj"), AllOf(HasSubstr("fart.obj"), HasSubstr("index out of range")));
}

// tinyobjloader's skin weights (`vw`, its own extension) are not read: a joint id past INT_MAX,
// which it converts to int unchecked (found by fuzzing), leaves the faces as they are.
TEST_F(ObjScene, SkinWeightsAreNotRead) {
  writeText("plain.obj", std::string(kSquareVertices) + "f 1/1 2/2 3/3\n");
  writeText("weights.obj", std::string(kSquareVertices) +
                               "vw 0 099803543091 6.44\n  vw\t1 5e30 1\nf 1/1 2/2 3/3\n");
  const TexturedScene plain = load("plain.obj"), weighted = load("weights.obj");
  EXPECT_EQ(weighted.positions, plain.positions);
  EXPECT_EQ(weighted.uvs, plain.uvs);
  EXPECT_EQ(weighted.indices, plain.indices);
  EXPECT_EQ(weighted.indices.size(), 3u);
}

// A map whose header claims 65535 x 65535 texels and whose file holds no pixel is believed only
// as far as it decodes: the checker, not a texture area for four billion texels.
TEST_F(ObjScene, AMapWhoseHeaderLiesAboutItsSizeIsDrawnAsTheChecker) {
  // TGA, uncompressed true colour, 32 bits per pixel, 65535 x 65535, and nothing after the header.
  const unsigned char header[18] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0xff, 0xff,
                                    32, 8};
  std::ofstream(dir_ / "liar.tga", std::ios::binary)
      .write(reinterpret_cast<const char*>(header), sizeof header);
  writeText("scene.mtl", "newmtl liar\nmap_Kd liar.tga\n");
  writeText("scene.obj", std::string("mtllib scene.mtl\n") + kSquareVertices +
                             "usemtl liar\nf 1/1 2/2 3/3\n");
  const TexturedScene scene = load("scene.obj");
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_TRUE(scene.textures[0].missing);
  EXPECT_EQ(scene.textures[0].width, kMissingTextureSide);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_THAT(scene.warnings[0], HasSubstr("liar.tga is not a readable image"));
}

TEST_F(ObjScene, MaterialsWithoutAReadableMapAreDrawnAsTheCheckerWithAWarning) {
  writeImage("good.png", 16, 16);
  writeText("scene.mtl",
            "newmtl plain\nKd 0.5 0.5 0.5\n"
            "newmtl lost\nmap_Kd lost.png\n"
            "newmtl good\nmap_Kd good.png\n");
  writeText("scene.obj", std::string("mtllib scene.mtl\n") + kSquareVertices +
                             "usemtl plain\nf 1/1 2/2 3/3\n"
                             "usemtl lost\nf 1/1 3/3 4/4\n"
                             "usemtl good\nf 1/1 2/2 4/4\n"
                             "usemtl plain\nf 2/2 3/3 4/4\n");
  const TexturedScene scene = load("scene.obj");
  ASSERT_EQ(scene.faces.size(), 4u);
  ASSERT_EQ(scene.textures.size(), 3u);
  EXPECT_EQ(scene.faces[0].texture, 0u);
  EXPECT_EQ(scene.faces[1].texture, 1u);
  EXPECT_EQ(scene.faces[2].texture, 2u);
  EXPECT_EQ(scene.faces[3].texture, 0u);  // one texture per material
  for (const uint32_t t : {0u, 1u}) {
    const SourceTexture& checker = scene.textures[t];
    EXPECT_TRUE(checker.missing) << t;
    EXPECT_EQ(checker.width, kMissingTextureSide) << t;
    EXPECT_EQ(checker.height, 64u) << t;
    EXPECT_TRUE(std::filesystem::equivalent(checker.file, dir_ / "images/missing_texture.png"));
  }
  EXPECT_EQ(scene.textures[0].name, "plain");
  EXPECT_EQ(scene.textures[1].name, "lost");
  EXPECT_FALSE(scene.textures[2].missing);
  EXPECT_EQ(scene.textures[2].width, 16u);
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_THAT(scene.warnings[0], AllOf(HasSubstr("plain"), HasSubstr("map_Kd")));
  EXPECT_THAT(scene.warnings[1], AllOf(HasSubstr("lost"), HasSubstr("lost.png")));
}

TEST_F(ObjScene, DiffuseMapIsRelativeToTheMaterialFile) {
  // obj_scene.h: "map_Kd, relative to the MTL file", here in a folder of its own.
  writeImage("materials/wall.png", 16, 8);
  writeText("materials/scene.mtl", "newmtl wall\nmap_Kd wall.png\n");
  writeText("scene.obj", std::string("mtllib materials/scene.mtl\n") + kSquareVertices +
                             "usemtl wall\nf 1/1 2/2 3/3\n");
  const TexturedScene scene = load("scene.obj");
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_FALSE(scene.textures[0].missing);
  EXPECT_EQ(scene.textures[0].width, 16u);
  EXPECT_EQ(scene.textures[0].height, 8u);
  EXPECT_TRUE(scene.warnings.empty());
}

TEST_F(ObjScene, NonFiniteVertexSkipsItsFace) {
  // tinyobjloader reads m e x as ldexp(m * 5^x, x): 0e500 is 0 * inf, NaN; 1e400 overflows to
  // infinity.
  writeText("nan.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0e500 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 1e400 0\n"
            "f 1/1 2/2 3/3\n"
            "f 1/1 3/3 4/1\n"  // NaN position
            "f 1/1 2/2 3/4\n"  // infinite s
            "f 2/2 3/3 1/1\n");
  const TexturedScene scene = load("nan.obj");
  EXPECT_EQ(scene.skipped.notFinite, 2u);
  EXPECT_EQ(scene.skipped.total(), 2u);
  ASSERT_EQ(scene.faces.size(), 2u);
  EXPECT_EQ(scene.positions.size(), 6u);
  EXPECT_EQ(scene.positions[3], glm::vec3(1.0f, 0.0f, 0.0f));  // the last face's first corner
  for (const glm::vec3& p : scene.positions) EXPECT_TRUE(std::isfinite(p.x));
  // Faces without a material: the checker, with one warning.
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_TRUE(scene.textures[0].missing);
  EXPECT_EQ(scene.warnings.size(), 1u);
}

}  // namespace
}  // namespace vt
