#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "common/error.h"
#include "scene/box_room.h"
#include "scene/camera.h"
#include "scene/obj_mesh.h"
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

TEST(ObjMesh, LoadsTrianglesAndFlipsV) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "quad.obj")
      << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
         "f 1/1 2/2 3/3 4/4\n";
  const Mesh mesh = loadObjMesh(dir / "quad.obj");
  ASSERT_EQ(mesh.indices.size(), 6u);  // the quad, triangulated
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    // OBJ's v = 0 is the texture's last row (t = 1): here vt equals the position's (x, y).
    EXPECT_EQ(mesh.uvs[v], glm::vec2(mesh.positions[v].x, 1.0f - mesh.positions[v].y));
  }
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
