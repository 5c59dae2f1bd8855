// The oracle's public API (<vt/oracle.h>): the same frames as the renderer it wraps, comparisons
// that name the pixel that differs, and captures that round-trip through their files and are
// refused, with the file and the problem named, when malformed or inconsistent.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "build/synthetic_texture.h"
#include "reference/api/api_internal.h"
#include "reference/renderer.h"
#include "render/arithmetic_points.h"
#include "render/precision_model.h"
#include "render/precision_model_file.h"
#include "scene/obj_mesh.h"
#include "scene/test_scenes.h"
#include "test_support.h"
#include "vt/oracle.h"

namespace vt {
namespace {

using ::testing::HasSubstr;

const SyntheticTexture kTexture{{.pageSize = 32, .border = 2, .levelCount = 6, .channels = 4},
                                std::nullopt};

oracle::Scene publicScene(const std::string& name, oracle::Viewport viewport) {
  const NamedScene scene = testScene(name);
  const Viewport size{viewport.width, viewport.height};
  return oracle::publicScene(toClipSpace(scene.mesh, scene.camera, size), size);
}

// The first pixel with geometry whose result set is one value.
size_t firstClearPixel(const oracle::Frame& frame) {
  for (size_t i = 0; i < frame.ambiguous.size(); ++i)
    if (frame.ambiguous[i] == 0 && frame.color[i * 4 + 3] != 0) return i;
  ADD_FAILURE() << "no unambiguous pixel with geometry";
  return 0;
}

// sceneFromObj: the OBJ's polygons fanned as the project's loaders fan them, each vertex through
// the transform both renderers use (bit for bit the internal toClipSpace), OBJ's v flipped;
// an unreadable file is an Error naming it.
TEST(OracleApi, SceneFromObjIsTheRenderersTransformOfTheMesh) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "quad.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
  oracle::Camera camera;
  camera.position[2] = 3.0f;
  camera.fovYDegrees = 50.0f;
  const oracle::Scene scene = oracle::sceneFromObj(dir / "quad.obj", camera, {64, 48});
  EXPECT_EQ(scene.viewport.width, 64);
  EXPECT_EQ(scene.viewport.height, 48);
  ASSERT_EQ(scene.vertices.size(), 4u);
  EXPECT_EQ(scene.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));

  Camera internal;
  internal.position = glm::vec3(0, 0, 3);
  internal.target = glm::vec3(0);
  internal.fovYDegrees = 50.0f;
  const ClipSpaceMesh expected =
      toClipSpace(loadObjMesh(dir / "quad.obj"), internal, Viewport{64, 48});
  for (size_t i = 0; i < 4; ++i) {
    const oracle::ClipVertex& v = scene.vertices[i];
    EXPECT_EQ(glm::vec4(v.x, v.y, v.z, v.w), expected.vertices[i].position) << i;
    EXPECT_EQ(glm::vec2(v.s, v.t), expected.vertices[i].uv) << i;
  }
  EXPECT_EQ(glm::vec2(scene.vertices[3].s, scene.vertices[3].t), glm::vec2(0, 0));  // vt (0, 1)
  EXPECT_GT(scene.vertices[0].w, 0.0f);

  std::ofstream(dir / "broken.obj") << "v 0 0 0\nf 1 1 1\n";
  EXPECT_THAT(
      [&] {
        oracle::sceneFromObj(dir / "broken.obj", camera, {64, 48});
      },
      ::testing::ThrowsMessage<oracle::Error>(HasSubstr("broken.obj")));
  EXPECT_THAT(
      [&] {
        oracle::sceneFromObj(dir / "missing.obj", camera, {64, 48});
      },
      ::testing::ThrowsMessage<oracle::Error>(HasSubstr("missing.obj")));
}

TEST(OracleApi, RendersTheSameFrameAsTheOracleItWraps) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt", kTexture);
  const oracle::Texture texture = oracle::Texture::open(dir / "t.vt");
  EXPECT_EQ(texture.pageSize(), 32u);
  EXPECT_EQ(texture.levelCount(), 6u);
  EXPECT_EQ(texture.side(), 1024u);
  EXPECT_TRUE(texture.contains(5, 31, 31));
  EXPECT_FALSE(texture.contains(5, 32, 0));

  const oracle::Scene scene = publicScene("room", {96, 64});
  oracle::RenderOptions options;
  options.profile = oracle::Profile::kLlvmpipe;
  options.needEncoding = oracle::NeedEncoding::k8Bit;
  const oracle::Frame frame =
      oracle::render(texture, scene, oracle::CacheState::everything(), options);

  const VirtualTextureReader reader(dir / "t.vt");
  const reference::ResidentTexture everything(reader);
  RenderSettings settings;
  settings.viewport = {96, 64};
  settings.arithmetic = arithmeticPoint("llvmpipe");
  settings.need8 = true;
  const NamedScene named = testScene("room");
  const Frame expected = reference::renderFrame(
      toClipSpace(named.mesh, named.camera, settings.viewport), everything, settings);
  EXPECT_EQ(frame.color, expected.color);
  EXPECT_EQ(frame.depth, expected.depth);
  EXPECT_EQ(frame.model, "llvmpipe");
  EXPECT_EQ(frame.ambiguous, std::vector<uint8_t>(frame.ambiguous.size(), 0));
  EXPECT_FALSE(frame.sets);
  ASSERT_EQ(frame.need.size(), expected.need.size() * 4);
  for (size_t i = 0; i < expected.need.size(); ++i)
    ASSERT_EQ(glm::uvec4(frame.need[i * 4], frame.need[i * 4 + 1], frame.need[i * 4 + 2],
                         frame.need[i * 4 + 3]),
              expected.need[i]);
}

TEST(OracleApi, CacheStatesAreValidatedAndDriveTheLookup) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt", kTexture);
  const oracle::Texture texture = oracle::Texture::open(dir / "t.vt");
  const oracle::Scene scene = publicScene("room", {64, 48});
  oracle::CacheState rootOnly{false, 2, 2, {{0, 0, 0, 1, 1}}};
  const oracle::Frame coarse = oracle::render(texture, scene, rootOnly, {});
  const oracle::Frame fine = oracle::render(texture, scene, oracle::CacheState::everything(), {});
  // Needbuffers do not depend on the cache; colours do (only the root's texels are there).
  EXPECT_EQ(coarse.need, fine.need);
  EXPECT_NE(coarse.color, fine.color);

  const auto refused = [&](oracle::CacheState cache, const std::string& message) {
    try {
      (void)oracle::render(texture, scene, cache, {});
      ADD_FAILURE() << "accepted: " << message;
    } catch (const oracle::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  refused({false, 2, 2, {{1, 0, 0, 0, 0}}}, "root page (0) is not resident");
  refused({false, 2, 2, {{0, 0, 0, 0, 0}, {1, 1, 0, 0, 0}}}, "already holds a page");
  refused({false, 2, 2, {{0, 0, 0, 2, 0}}}, "lies outside the 2 x 2 frames");
  refused({false, 2, 2, {{0, 0, 0, 0, 0}, {0, 0, 0, 1, 0}}}, "resident twice");
  refused({false, 2, 2, {{0, 0, 0, 0, 0}, {6, 0, 0, 1, 0}}}, "not stored in the texture");
  refused({false, 2, 2, {{0, 0, 0, 0, 0}, {2, 4, 0, 1, 0}}}, "does not exist");

  // A prepared state draws the same frame as the state it was prepared from, for its own texture.
  const oracle::PreparedCache prepared(texture, rootOnly);
  EXPECT_EQ(oracle::render(texture, scene, prepared, {}).color, coarse.color);
  const oracle::Texture other = oracle::Texture::open(dir / "t.vt");
  try {
    (void)oracle::render(other, scene, prepared, {});
    ADD_FAILURE() << "rendered with a cache prepared for another texture";
  } catch (const oracle::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("prepared for another texture"));
  }
}

TEST(OracleApi, ComparisonNamesExactlyTheChangedPixel) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt", kTexture);
  const oracle::Texture texture = oracle::Texture::open(dir / "t.vt");
  const oracle::Frame frame = oracle::render(texture, publicScene("grazing", {80, 60}),
                                             oracle::CacheState::everything(), {});
  EXPECT_TRUE(oracle::compare(frame, frame.color, frame.need).passed());

  std::vector<uint32_t> need = frame.need;
  const size_t pixel = firstClearPixel(frame);
  need[pixel * 4 + 2] += 1;  // another level
  const oracle::Comparison c = oracle::compare(frame, frame.color, need);
  EXPECT_FALSE(c.passed());
  EXPECT_EQ(c.unexplained, 1u);
  EXPECT_EQ(c.needMismatched, 1u);
  ASSERT_EQ(c.mismatches.size(), 1u);
  EXPECT_EQ(c.mismatches[0].x, static_cast<int>(pixel % 80));
  EXPECT_EQ(c.mismatches[0].y, static_cast<int>(pixel / 80));
  EXPECT_EQ(c.mismatches[0].actualNeed[2], frame.need[pixel * 4 + 2] + 1);
  EXPECT_EQ(oracle::reasonName(c.mismatches[0].reason), "lod");
  EXPECT_EQ(c.mismatches[0].widenBy, 1.0);

  // Under the pinned exact model, a colour 4 units off is unexplained, and the filter would have
  // to widen by exactly 4.
  std::vector<uint8_t> color = frame.color;
  color[pixel * 4] =
      static_cast<uint8_t>(color[pixel * 4] < 128 ? color[pixel * 4] + 4 : color[pixel * 4] - 4);
  const oracle::Comparison off = oracle::compare(frame, color, frame.need);
  EXPECT_EQ(off.unexplained, 1u);
  EXPECT_EQ(off.ambiguous, 0u);
  ASSERT_EQ(off.mismatches.size(), 1u);
  EXPECT_EQ(oracle::reasonName(off.mismatches[0].reason), "filter");
  EXPECT_EQ(off.mismatches[0].widenBy, 4.0);
  EXPECT_THAT(
      [&] { oracle::compare(frame, std::span(color).first(8), frame.need); },
      ::testing::ThrowsMessage<oracle::Error>(HasSubstr("compare: the frame has 2 colour")));
}

// Given the frame it will judge, the oracle builds sets where that frame differs and reaches the
// verdict every pixel's sets reach; compare() refuses a frame that differs where no set was built.
TEST(OracleApi, AJudgedFrameGetsSetsWhereItDiffersAndTheSameVerdict) {
  test::ScratchDirectory dir;
  writeSyntheticTexture(dir / "t.vt", kTexture);
  const oracle::Texture texture = oracle::Texture::open(dir / "t.vt");
  const oracle::Scene scene = publicScene("grazing", {80, 60});
  oracle::RenderOptions options;
  options.profile = oracle::Profile::kGl45;
  const oracle::Frame every =
      oracle::render(texture, scene, oracle::CacheState::everything(), options);
  EXPECT_FALSE(every.judged);
  // Three covered pixels changed: red by 1 (inside its set) and by 90 (outside), a level more.
  std::vector<uint8_t> color = every.color;
  std::vector<uint32_t> need = every.need;
  std::vector<size_t> covered;
  for (size_t i = 0; i < every.ambiguous.size() && covered.size() < 3; i += 97)
    if (every.color[i * 4 + 3] != 0) covered.push_back(i);
  ASSERT_EQ(covered.size(), 3u);
  color[covered[0] * 4] = static_cast<uint8_t>(color[covered[0] * 4] ^ 1);
  color[covered[1] * 4] = static_cast<uint8_t>(color[covered[1] * 4] + 90);
  need[covered[2] * 4 + 2] += 1;
  options.judgedColor = color;
  options.judgedNeed = need;
  const oracle::Frame judged =
      oracle::render(texture, scene, oracle::CacheState::everything(), options);
  EXPECT_TRUE(judged.judged);
  EXPECT_EQ(judged.color, every.color);
  const oracle::Comparison a = oracle::compare(every, color, need);
  const oracle::Comparison b = oracle::compare(judged, color, need);
  EXPECT_EQ(a.identical, every.ambiguous.size() - 3);
  EXPECT_EQ(b.identical, a.identical);
  EXPECT_EQ(b.explained, a.explained);
  EXPECT_EQ(b.unexplained, a.unexplained);
  EXPECT_GE(b.unexplained, 1u);
  EXPECT_EQ(b.explainedBy, a.explainedBy);
  EXPECT_TRUE(b.judged);
  EXPECT_LE(b.ambiguous, 3u);  // only the differing pixels' sets are known
  EXPECT_GT(a.ambiguous, 100u);

  // Another frame: it differs at a pixel the judged one matched.
  std::vector<uint8_t> other = every.color;
  other[(covered[0] + 1) * 4 + 1] ^= 4;
  try {
    (void)oracle::compare(judged, other, every.need);
    ADD_FAILURE() << "compared a frame the sets were not built for";
  } catch (const oracle::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("built against another frame"));
  }
  options.judgedNeed = std::span(need).first(40);
  try {
    (void)oracle::render(texture, scene, oracle::CacheState::everything(), options);
    ADD_FAILURE() << "rendered against a judged frame of another size";
  } catch (const oracle::Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("judged frame has 4800 colour and 10 needbuffer pixels"));
  }
}

// A capture of the oracle's own frame, written and read back.
struct CaptureFixture {
  test::ScratchDirectory dir;
  std::filesystem::path manifest;
  oracle::Capture capture;

  explicit CaptureFixture(oracle::NeedEncoding encoding) {
    writeSyntheticTexture(dir / "t.vt", kTexture);
    const oracle::Texture texture = oracle::Texture::open(dir / "t.vt");
    capture.renderer = "test renderer";
    capture.texture = dir / "t.vt";
    capture.textureIdentity = texture.identity();
    capture.scene = publicScene("minified", {72, 40});
    capture.cache = {false, 4, 4, {{0, 0, 0, 3, 3}, {1, 0, 0, 0, 0}, {1, 1, 1, 2, 1}}};
    capture.needEncoding = encoding;
    const oracle::Frame frame =
        oracle::render(texture, capture.scene, capture.cache,
                       oracle::renderOptions(capture, oracle::Profile::kExact));
    capture.color = frame.color;
    capture.need = frame.need;
    std::filesystem::create_directories(dir / "captures");
    manifest = dir / "captures" / "frame0000.json";
    oracle::writeCapture(manifest, capture);
  }

  nlohmann::json manifestJson() const {
    std::ifstream in(manifest);
    return nlohmann::json::parse(in);
  }
  void rewrite(const nlohmann::json& json) const { std::ofstream(manifest) << json.dump(2); }
};

TEST(OracleApi, CapturesRoundTripThroughTheirFiles) {
  for (const oracle::NeedEncoding encoding :
       {oracle::NeedEncoding::k32Bit, oracle::NeedEncoding::k8Bit}) {
    SCOPED_TRACE(oracle::toString(encoding));
    CaptureFixture f(encoding);
    const oracle::Capture read = oracle::readCapture(f.manifest);
    EXPECT_EQ(read.renderer, "test renderer");
    EXPECT_EQ(std::filesystem::canonical(read.texture), std::filesystem::canonical(f.dir / "t.vt"));
    EXPECT_EQ(f.manifestJson()["texture"]["file"], "../t.vt");
    EXPECT_EQ(read.textureIdentity, f.capture.textureIdentity);
    EXPECT_EQ(read.needEncoding, encoding);
    EXPECT_EQ(read.scene.vertices.size(), f.capture.scene.vertices.size());
    EXPECT_EQ(0, std::memcmp(read.scene.vertices.data(), f.capture.scene.vertices.data(),
                             read.scene.vertices.size() * sizeof(oracle::ClipVertex)));
    EXPECT_EQ(read.scene.indices, f.capture.scene.indices);
    EXPECT_EQ(read.cache.pages.size(), 3u);
    EXPECT_EQ(read.cache.pages[2].frameX, 2u);
    EXPECT_EQ(read.color, f.capture.color);
    EXPECT_EQ(read.need, f.capture.need);
    EXPECT_TRUE(read.model.empty()) << "a capture that names no model file";
    EXPECT_FALSE(f.manifestJson().contains("model"));
    const oracle::CaptureCheck check =
        oracle::checkCapture(read, oracle::Texture::open(read.texture), oracle::Profile::kExact);
    EXPECT_EQ(check.comparison.identical, 72u * 40u);
  }
}

// A capture may name the model file that judges it: written relative to the manifest's folder,
// read back resolved against it, and usable as the model of checkCapture.
TEST(OracleApi, ACapturesModelFileRoundTripsAndJudgesIt) {
  CaptureFixture f(oracle::NeedEncoding::k32Bit);
  std::filesystem::create_directories(f.dir / "models");
  std::ofstream(f.dir / "models" / "exact.json") << modelJson(exactModel());
  f.capture.model = f.dir / "models" / "exact.json";
  oracle::writeCapture(f.manifest, f.capture);
  EXPECT_EQ(f.manifestJson()["model"], "../models/exact.json");
  const oracle::Capture read = oracle::readCapture(f.manifest);
  EXPECT_EQ(std::filesystem::canonical(read.model),
            std::filesystem::canonical(f.dir / "models" / "exact.json"));
  const oracle::CaptureCheck check =
      oracle::checkCapture(read, oracle::Texture::open(read.texture), read.model);
  EXPECT_EQ(check.comparison.model, "exact");
  EXPECT_EQ(check.comparison.identical, 72u * 40u);
}

TEST(OracleApi, MalformedOrInconsistentCapturesAreRefusedWithTheFileNamed) {
  const auto refused = [](const std::filesystem::path& manifest, const std::string& message) {
    try {
      (void)oracle::readCapture(manifest);
      ADD_FAILURE() << "accepted: " << message;
    } catch (const oracle::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
  };
  const auto edited = [&](auto edit, const std::string& message) {
    CaptureFixture f(oracle::NeedEncoding::k32Bit);
    nlohmann::json json = f.manifestJson();
    edit(json, f);
    f.rewrite(json);
    SCOPED_TRACE(message);
    refused(f.manifest, message);
  };
  using J = nlohmann::json;
  using F = const CaptureFixture&;
  edited([](J& j, F) { j["needbuffer_encoding"] = "need16"; },
         "\"needbuffer_encoding\" is \"need16\", not one of need32, need8");
  edited([](J& j, F) { j["viewport"]["height"] = 41; },
         "image is 72 x 40 with 4 channels, the viewport 72 x 41 RGBA");
  edited(
      [](J&, F f) {
        std::vector<std::byte> need = test::readBytes(f.dir / "captures" / "frame0000.need.u32");
        need.erase(need.end() - 16, need.end());  // one pixel short
        test::writeBytes(f.dir / "captures" / "frame0000.need.u32", need);
      },
      "holds 46064 bytes, the manifest asks for 46080");
  edited([](J& j, F) { j["version"] = 2; }, "has version 2; this oracle reads version 1");
  edited([](J& j, F) { j.erase("filtering"); }, "manifest has no \"filtering\"");
  edited([](J& j, F) { j["sampling"] = 3; }, "\"sampling\" is not a string");
  edited([](J& j, F) { j["colour"] = "x.png"; }, "unknown field \"colour\"");
  edited([](J& j, F) { j["model"] = 7; }, "\"model\" is not a string");
  edited([](J& j, F) { j["model"] = ""; }, "\"model\" is an empty file name");
  edited([](J& j, F) { j["fingerprint"] = "nvidia"; },
         "\"fingerprint\" is not a shipped pinned model (exact, llvmpipe, softpipe)");
  edited([](J& j, F) { j["texture"]["identity"] = "xyz"; }, "not 16 hexadecimal digits");
  edited([](J& j, F) { j["geometry"]["vertices"] = "../../etc/passwd"; }, "without \"..\"");
  edited([](J& j, F) { j["geometry"]["index_count"] = 7; }, "holds");
  edited([](J& j, F) { j["geometry"]["vertex_count"] = uint64_t{1} << 40; }, "the limit is");
  edited(
      [](J& j, F) {
        j["cache"]["pages"][0] = J::array({0, 0, 0});
      },
      "is not [level, px, py, frame_x, frame_y]");
  edited([](J& j, F) { j["cache"]["frames_x"] = 0; }, "has no frames");
  edited([](J&, F f) { std::filesystem::remove(f.dir / "captures" / "frame0000.color.png"); },
         "frame0000.color.png");
  {
    CaptureFixture f(oracle::NeedEncoding::k32Bit);
    std::ofstream(f.manifest) << "{\"format\": \"vt-capture\", ";
    refused(f.manifest, "frame0000.json: [json.exception.parse_error");
  }
  {
    // Indices that name no vertex.
    CaptureFixture f(oracle::NeedEncoding::k32Bit);
    std::vector<std::byte> indices = test::readBytes(f.dir / "captures" / "frame0000.indices.u32");
    indices[0] = std::byte{0xff};
    indices[1] = std::byte{0xff};
    test::writeBytes(f.dir / "captures" / "frame0000.indices.u32", indices);
    refused(f.manifest, "names no vertex");
  }
  {
    // Another texture than the one the frame was drawn from.
    CaptureFixture f(oracle::NeedEncoding::k32Bit);
    SyntheticTexture other = kTexture;
    other.description.levelCount = 5;
    writeSyntheticTexture(f.dir / "t.vt", other);
    const oracle::Capture capture = oracle::readCapture(f.manifest);
    try {
      (void)oracle::checkCapture(capture, oracle::Texture::open(capture.texture),
                                 oracle::Profile::kExact);
      ADD_FAILURE() << "accepted another texture";
    } catch (const oracle::Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("does not match the capture's"));
    }
  }
}

}  // namespace
}  // namespace vt
