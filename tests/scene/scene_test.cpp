#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "common/error.h"
#include "scene/box_room.h"
#include "scene/camera.h"
#include "scene/obj_mesh.h"
#include "scene/obj_scene.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

TEST(Camera, LooksDownTheTargetDirection) {
  Camera camera;
  camera.position = {0, 0, 3};
  camera.target = {0, 0, 0};
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, -1}};
  mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  const ClipSpaceMesh clip = toClipSpace(mesh, camera, {100, 100});
  // The target lands on the screen's centre at w = its distance.
  EXPECT_NEAR(clip.vertices[0].position.x, 0.0f, 1e-6f);
  EXPECT_NEAR(clip.vertices[0].position.y, 0.0f, 1e-6f);
  EXPECT_NEAR(clip.vertices[0].position.w, 3.0f, 1e-6f);
  // +x is to the right, +y up; farther points have larger w.
  EXPECT_GT(clip.vertices[1].position.x, 0.0f);
  EXPECT_GT(clip.vertices[2].position.y, 0.0f);
  EXPECT_NEAR(clip.vertices[2].position.w, 4.0f, 1e-6f);
  EXPECT_EQ(clip.vertices[1].uv, glm::vec2(1, 0));
}

TEST(Camera, ParsesAndRejects) {
  const Camera camera = parseCamera("1,2,3:4,5,6:45");
  EXPECT_EQ(camera.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(camera.target, glm::vec3(4, 5, 6));
  EXPECT_EQ(camera.fovYDegrees, 45.0f);
  EXPECT_THAT([] { parseCamera("1,2,nan:0,0,0"); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                                        HasSubstr("'nan' is not a finite number")));
  EXPECT_THAT([] { parseCamera("1,2:0,0,0"); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                                    HasSubstr("expected x,y,z:tx,ty,tz")));
  EXPECT_THAT([] { parseCamera("1,1,1:1,1,1"); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("target equals")));
  EXPECT_THAT([] { parseCamera("0,0,1:0,0,0:180"); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("field of view")));
}

TEST(BoxRoom, MapsEveryFaceInsideTheTexture) {
  const Mesh room = boxRoom();
  EXPECT_EQ(room.indices.size(), 36u);
  for (const glm::vec2 uv : room.uvs) {
    EXPECT_GT(uv.x, 0.0f);
    EXPECT_LT(uv.x, 1.0f);
    EXPECT_GT(uv.y, 0.0f);
    EXPECT_LT(uv.y, 1.0f);
  }
}

// A quad whose diagonal 1-3 is the shorter one (a loader that picks the shorter diagonal would cut
// it there) and a pentagon: both loaders fan every polygon from its first corner, so the same OBJ
// draws the same triangles whether it is flown as a mesh or retextured as a scene. Each corner's
// vt is its position's (x / 16, y / 4), so the flip to t = 1 - v shows.
TEST(ObjMesh, BothLoadersFanPolygonsFromTheirFirstCornerAndFlipV) {
  test::ScratchDirectory dir;
  const std::vector<glm::vec3> corners = {{0, 0, 0},  {3, 0, 0},  {4, 4, 0},  {0, 1, 0}, {10, 0, 0},
                                          {11, 0, 0}, {12, 1, 0}, {11, 2, 0}, {10, 1, 0}};
  std::ofstream obj(dir / "polygons.obj");
  for (const glm::vec3& p : corners) obj << "v " << p.x << " " << p.y << " 0\n";
  for (const glm::vec3& p : corners) obj << "vt " << p.x / 16 << " " << p.y / 4 << "\n";
  obj << "f 1/1 2/2 3/3 4/4\nf 5/5 6/6 7/7 8/8 9/9\n";
  obj.close();
  const Mesh mesh = loadObjMesh(dir / "polygons.obj");
  const std::vector<uint32_t> fan = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 4, 7, 8};
  EXPECT_EQ(mesh.indices, fan);
  EXPECT_EQ(mesh.positions, corners);
  for (size_t v = 0; v < corners.size(); ++v)
    EXPECT_EQ(mesh.uvs[v], glm::vec2(corners[v].x / 16, 1.0f - corners[v].y / 4));

  const TexturedScene scene = loadObjScene(dir / "polygons.obj", dir / "images");
  EXPECT_EQ(scene.source, (dir / "polygons.obj").string());  // what refusals name
  EXPECT_EQ(scene.indices, fan);
  EXPECT_EQ(scene.positions, mesh.positions);
  EXPECT_EQ(scene.uvs, mesh.uvs);
  ASSERT_EQ(scene.faces.size(), 2u);
  EXPECT_EQ(scene.faces[1].firstIndex, 6u);
  EXPECT_EQ(scene.faces[1].indexCount, 9u);
}

TEST(ObjMesh, BadFilesNameTheProblem) {
  test::ScratchDirectory dir;
  EXPECT_THAT([&] { loadObjMesh(dir / "missing.obj"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("mesh not found")));
  std::ofstream(dir / "nouv.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
  EXPECT_THAT(
      [&] { loadObjMesh(dir / "nouv.obj"); },
      ::testing::ThrowsMessage<InputError>(HasSubstr("a face without texture coordinates")));
  std::ofstream(dir / "empty.obj") << "# nothing\n";
  EXPECT_THAT([&] { loadObjMesh(dir / "empty.obj"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("no triangles")));
}

}  // namespace
}  // namespace vt
