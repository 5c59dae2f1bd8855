// Sizes that would need absurd memory, disk or time (common/resource_limits.h) are refused before
// anything is allocated for them, with one line that names the file, what was asked and the
// limit. Each input here is small: the absurdity is in what it asks for.

#include "common/resource_limits.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <climits>
#include <string>
#include <vector>

#include "build/layout.h"
#include "build/texture_builder.h"
#include "common/little_endian.h"
#include "format/file_header.h"
#include "format/page_address.h"
#include "retexture/face_charts.h"
#include "retexture/page_grid_layout.h"
#include "scene/camera_path.h"
#include "scene/package_files.h"
#include "scene/quake3_fixtures.h"
#include "scene/quake3_scene.h"
#include "scene/texture_resolver.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

// ---------------------------------------------------------------------------------------------
// Virtual-texture headers

// A header whose every field is consistent, for `storedPages` pages of 128^2 RGBA texels.
std::array<std::byte, kHeaderBytes> headerFor(uint32_t levels, bool sparse, uint64_t storedPages) {
  FileHeader header;
  header.description = {.pageSize = 128, .border = 4, .levelCount = levels, .channels = 4};
  header.sparse = sparse;
  header.storedPageCount = storedPages;
  header.layout = layoutFor(header.description, sparse, storedPages);
  return encodeHeader(header);
}

TEST(ResourceLimits, HeaderAskingForMorePagesThanTheLimitIsRefusedBeforeItsTables) {
  // A dense texture of 16 levels, and a sparse one just over the limit; both declare files of
  // tens of terabytes (the file size is checked after the count, so no table is ever read).
  const uint64_t dense = pageCount(15);
  for (const auto& [header, pages] :
       {std::pair{headerFor(16, false, dense), dense},
        std::pair{headerFor(16, true, kMaxStoredPages + 1), kMaxStoredPages + 1}}) {
    const auto& bytes = header;  // clang 14 cannot capture a structured binding in a lambda
    const uint64_t fileBytes = loadU64(bytes.data() + 88);
    EXPECT_THAT([&] { decodeHeader(bytes, fileBytes, "huge.vt"); },
                ThrowsMessage<InputError>("huge.vt: header field stored_page_count asks for " +
                                          std::to_string(pages) + " pages, the limit is " +
                                          std::to_string(kMaxStoredPages) + " pages"));
  }
  // At the limit the header is accepted.
  const auto header = headerFor(16, true, kMaxStoredPages);
  EXPECT_EQ(decodeHeader(header, loadU64(header.data() + 88), "large.vt").storedPageCount,
            kMaxStoredPages);
}

// ---------------------------------------------------------------------------------------------
// Layouts

// Images are not opened: every one is `image` in size.
Layout layoutOf(const std::string& text, ImageInfo image) {
  return parseLayout(text, "/layouts/layout.json", {},
                     [image](const std::filesystem::path&, const std::string&) { return image; });
}

TEST(ResourceLimits, BuildWhoseRowRingsNeedMoreMemoryThanTheLimitIsRefusedBeforeAnyAllocation) {
  // The widest texture the format allows, 4096 * 2^15 texels a side, with a small image repeated
  // across its whole width: every 256-column strip of the finest level holds 4,114 rows.
  test::ScratchDirectory dir;
  const Layout layout = layoutOf(R"({"page_size": 4096, "side": 134217728,
                                      "images": [{"file": "a.png", "x": 0, "y": 0,
                                                  "width": 134217728, "height": 64}]})",
                                 {64, 64, 3});
  const uint64_t asked = ringBytesBound(layout);
  EXPECT_GT(asked, kMaxBuildRingBytes);
  EXPECT_THAT([&] { buildVirtualTexture(layout, dir / "huge.vt", {.progress = false}); },
              ThrowsMessage<InputError>(
                  "/layouts/layout.json: building a 134217728^2-texel texture (3 channels, "
                  "page size 4096, box filter) asks for " +
                  std::to_string(asked) + " bytes of row rings, the limit is " +
                  std::to_string(kMaxBuildRingBytes) + " bytes of row rings"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(ResourceLimits, RegionOfAnImageTooLargeToDecodeWholeIsRefused) {
  const char* const text = R"({"images": [{"file": "huge.png", "x": 0, "y": 0,
                                           "width": 16, "height": 16}]})";
  EXPECT_THAT(
      [&] {
        layoutOf(text, {40000, 40000, 3});
      },
      ThrowsMessage<InputError>(
          "/layouts/huge.png: decoding the 40000 x 40000 image whole for the region of "
          "/layouts/layout.json images[0] asks for 4800000000 bytes, the limit is " +
          std::to_string(kMaxWholeImageBytes) + " bytes"));
  // Placed whole, the same image is streamed by scanlines: only the texture's size limits it.
  EXPECT_NO_THROW(
      layoutOf(R"({"images": [{"file": "huge.png", "x": 0, "y": 0}]})", {40000, 40000, 3}));
}

TEST(ResourceLimits, LayoutAskingForMorePagesThanTheLimitIsRefusedBeforeListingThem) {
  // One region placement as wide as the texture: 2^30 pages on the finest level alone.
  test::ScratchDirectory dir;
  const Layout layout = layoutOf(R"({"page_size": 8, "side": 262144, "channels": 1,
                                      "images": [{"file": "a.png", "x": 0, "y": 0,
                                                  "width": 262144, "height": 262144}]})",
                                 {64, 64, 1});
  EXPECT_THAT([&] { buildVirtualTexture(layout, dir / "huge.vt", {.progress = false}); },
              ThrowsMessage<InputError>(AllOf(StartsWith("/layouts/layout.json: the texture would "
                                                         "store up to "),
                                              HasSubstr("more than the limit of 268435456"))));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// ---------------------------------------------------------------------------------------------
// Quake 3 maps and archives

// `surfaces` patch surfaces sharing one control grid of 3 x `height` points.
std::vector<uint8_t> mapOfSharedPatches(int32_t height, int surfaces) {
  test::BspBuilder map;
  map.shaders.push_back({"textures/base/wall", 0, 0});
  for (int32_t i = 0; i < 3 * height; ++i)
    map.vertices.push_back({glm::vec3(static_cast<float>(i % 3), static_cast<float>(i / 3), 0.0f),
                            glm::vec2(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)});
  BspSurface patch;
  patch.type = static_cast<int32_t>(BspSurfaceType::kPatch);
  patch.vertexCount = 3 * height;
  patch.patchWidth = 3;
  patch.patchHeight = height;
  map.surfaces.assign(static_cast<size_t>(surfaces), patch);
  return map.build();
}

TexturedScene sceneOf(const std::vector<uint8_t>& bytes) {
  const BspFile bsp = parseBsp(bytes, "maps/shared.bsp");
  return quake3Scene(bsp, "maps/shared.bsp",
                     [](int32_t, const std::string& name, TexturedScene& scene) {
                       SourceTexture texture;
                       texture.name = name;
                       scene.textures.push_back(texture);
                       return static_cast<uint32_t>(scene.textures.size() - 1);
                     });
}

TEST(ResourceLimits, MapWhoseSurfacesTessellateToTooManyVerticesIsRefusedBeforeTessellating) {
  // 770 surfaces share 1,821 control points: a 160 KB file asking for 16.8 million vertices.
  const std::vector<uint8_t> bytes = mapOfSharedPatches(607, 770);
  EXPECT_LT(bytes.size(), 200'000u);
  const uint64_t perSurface = (1 * 8 + 1) * (303 * 8 + 1);
  EXPECT_THAT(
      [&] { sceneOf(bytes); },
      ThrowsMessage<InputError>(
          "maps/shared.bsp: tessellating the drawn surfaces (patches at level 8) asks for " +
          std::to_string(770 * perSurface) + " vertices, the limit is " +
          std::to_string(kMaxMapVertices) + " vertices"));
  // A few of them make an ordinary scene.
  EXPECT_EQ(sceneOf(mapOfSharedPatches(607, 7)).faces.size(), 7u);
}

TEST(ResourceLimits, MapWhosePolygonsShareOneIndexRangeTooOftenIsRefused) {
  test::BspBuilder map;
  map.shaders.push_back({"textures/base/wall", 0, 0});
  for (int i = 0; i < 3; ++i)
    map.vertices.push_back({glm::vec3(static_cast<float>(i), static_cast<float>(i % 2), 0.0f),
                            glm::vec2(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)});
  map.indices.resize(30'000);
  for (size_t i = 0; i < map.indices.size(); ++i) map.indices[i] = static_cast<int32_t>(i % 3);
  BspSurface polygon;
  polygon.type = static_cast<int32_t>(BspSurfaceType::kPolygon);
  polygon.vertexCount = 3;
  polygon.indexCount = 30'000;
  map.surfaces.assign(2300, polygon);  // 69 million indices from a 360 KB file
  EXPECT_THAT([&] { parseBsp(map.build(), "maps/shared.bsp"); },
              ThrowsMessage<InputError>(
                  "maps/shared.bsp: the triangle list of the polygon and mesh surfaces asks for "
                  "69000000 indices, the limit is 67108864 indices"));
}

// The byte offset of the first `signature` (a little-endian u32) in `bytes`.
size_t find(const std::vector<uint8_t>& bytes, uint32_t signature) {
  for (size_t i = 0; i + 4 <= bytes.size(); ++i)
    if (bytes[i] == (signature & 255) && bytes[i + 1] == ((signature >> 8) & 255) &&
        bytes[i + 2] == ((signature >> 16) & 255) && bytes[i + 3] == signature >> 24)
      return i;
  return bytes.size();
}

// A one-entry archive of `contents`, deflated, whose local and central headers then claim
// `claimed` bytes once inflated.
std::vector<uint8_t> archiveClaiming(const test::ScratchDirectory& dir, const std::string& contents,
                                     uint32_t claimed) {
  test::writeZip(dir / "a.pk3", {{"maps/a.bsp", contents}});
  const std::vector<std::byte> read = test::readBytes(dir / "a.pk3");
  std::vector<uint8_t> bytes(read.size());
  for (size_t i = 0; i < read.size(); ++i) bytes[i] = std::to_integer<uint8_t>(read[i]);
  test::putI32(bytes, find(bytes, 0x04034b50) + 22, static_cast<int32_t>(claimed));
  test::putI32(bytes, find(bytes, 0x02014b50) + 24, static_cast<int32_t>(claimed));
  return bytes;
}

TEST(ResourceLimits, ArchiveEntryClaimingMoreThanTheLimitIsRefusedBeforeInflating) {
  test::ScratchDirectory dir;
  const PackageFiles files =
      PackageFiles::fromMemory("huge.pk3", archiveClaiming(dir, "IBSP", 300'000'000));
  EXPECT_THAT([&] { files.read("maps/a.bsp"); },
              ThrowsMessage<InputError>(
                  "huge.pk3: entry 'maps/a.bsp' asks for 300000000 bytes, the limit is " +
                  std::to_string(kMaxPackageEntryBytes) + " bytes"));
}

TEST(ResourceLimits, ArchiveEntryInflatingBeyondWhatItClaimsStopsThere) {
  // 16 MB of zeros deflate to a few KB; the entry claims 10 bytes.
  test::ScratchDirectory dir;
  const PackageFiles files =
      PackageFiles::fromMemory("bomb.pk3", archiveClaiming(dir, std::string(16 << 20, '\0'), 10));
  EXPECT_THAT([&] { files.read("maps/a.bsp"); },
              ThrowsMessage<InputError>(StartsWith("bomb.pk3: entry 'maps/a.bsp': ")));
}

// A shader script is tokenised whole, so a 5 MiB one (of spaces, deflated to a few KB) is refused
// from the archive's directory before it is inflated.
TEST(ResourceLimits, ShaderScriptLargerThanTheLimitIsRefusedBeforeTokenising) {
  test::ScratchDirectory dir;
  test::writeZip(dir / "big.pk3", {{"scripts/big.shader", std::string(5 << 20, ' ')}});
  const PackageFiles files = PackageFiles::fromFolders({dir.path()});
  EXPECT_THAT(
      [&] { TextureResolver resolver(files); },
      ThrowsMessage<InputError>(
          (dir / "big.pk3").string() +
          ": entry 'scripts/big.shader' asks for 5242880 bytes, the limit is 4194304 bytes"));
}

// ---------------------------------------------------------------------------------------------
// Retexturing

// `faces` faces of one texture, each a fan of `triangles` triangles around the origin, all in the
// plane z = 0 with one texture map: every two meet at the origin, and with `shared`, at every
// vertex.
TexturedScene facesMeetingAtTheOrigin(uint32_t faces, uint32_t triangles, bool shared) {
  TexturedScene scene;
  scene.name = "fans";
  SourceTexture texture;
  texture.name = "t", texture.width = 64, texture.height = 64;
  scene.textures.push_back(texture);
  for (uint32_t f = 0; f < faces; ++f) {
    const auto first = static_cast<uint32_t>(scene.indices.size());
    const auto center = static_cast<uint32_t>(scene.positions.size());
    scene.positions.emplace_back(0.0f);
    scene.uvs.emplace_back(0.0f);
    for (uint32_t k = 0; k <= triangles; ++k) {
      // Points on a line, distinct between faces unless shared.
      const float x = 1.0f + static_cast<float>(k),
                  y = shared ? 1.0f : 1.0f + static_cast<float>(f);
      scene.positions.emplace_back(x, y, 0.0f);
      scene.uvs.emplace_back(x / 64.0f, y / 64.0f);
    }
    for (uint32_t k = 0; k < triangles; ++k)
      scene.indices.insert(scene.indices.end(), {center, center + 1 + k, center + 2 + k});
    scene.faces.push_back({.texture = 0, .firstIndex = first, .indexCount = 3 * triangles});
  }
  return scene;
}

// Faces that share their vertices many times over (a map whose surfaces name one index range
// again and again) would pair every two faces at every shared position: refused from the count
// before any pair is formed, and so are pairs whose vertex checks would exceed their limit.
TEST(ResourceLimits, FacesSharingVerticesManyTimesOverAreRefusedBeforeTheyArePaired) {
  // 300 faces at 102 shared positions: 102 * 300 * 299 / 2 pairs.
  EXPECT_THAT([&] { buildCharts(facesMeetingAtTheOrigin(300, 100, true), ChartOptions{}); },
              ThrowsMessage<InputError>("fans: pairing the faces that share a vertex position "
                                        "(every two at each position) asks for 4574700 pairs, "
                                        "the limit is 4194304 pairs"));
  // 2,000 faces meeting at the origin only: 1,999,000 pairs of 12 triangles each.
  EXPECT_THAT(
      [&] { buildCharts(facesMeetingAtTheOrigin(2000, 12, false), ChartOptions{}); },
      ThrowsMessage<InputError>("fans: checking whether the faces of 1999000 pairs lie in one "
                                "plane with one texture map asks for 71964000 vertices, the limit "
                                "is 67108864 vertices"));
  // Fewer make ordinary charts.
  EXPECT_EQ(buildCharts(facesMeetingAtTheOrigin(30, 100, true), ChartOptions{}).size(), 1u);
}

// A refusal about a map's contents names the file it came from (the .bsp, or the package entry),
// not the map's short name: the user has to find the file.
TEST(ResourceLimits, RetextureRefusalsNameTheFileTheSceneCameFrom) {
  TexturedScene shared = facesMeetingAtTheOrigin(300, 100, true);
  shared.source = "packages/pak0.pk3:maps/fans.bsp";
  EXPECT_THAT(
      [&] { buildCharts(shared, ChartOptions{}); },
      ThrowsMessage<InputError>(StartsWith("packages/pak0.pk3:maps/fans.bsp: pairing the faces")));
  // A face whose coordinates repeat its texture beyond the largest texture of the format.
  TexturedScene repeated = facesMeetingAtTheOrigin(1, 1, false);
  repeated.source = "maps/repeats.bsp";
  for (glm::vec2& uv : repeated.uvs) uv *= 1e7f;
  EXPECT_THAT(
      [&] { layoutOnPageGrid(repeated, 128); },
      ThrowsMessage<InputError>(StartsWith("maps/repeats.bsp: a face repeats its texture")));
  // The loaders record the file: a map read from its bytes names the file it was given.
  EXPECT_EQ(sceneOf(mapOfSharedPatches(607, 7)).source, "maps/shared.bsp");
}

// ---------------------------------------------------------------------------------------------
// Camera paths

TEST(ResourceLimits, CameraPathAskingForMoreFramesThanTheLimitIsRefused) {
  const auto pathTo = [](long long frame) {
    return R"({"keyframes": [{"frame": 0, "position": [0, 0, 0], "target": [0, 0, -1]},
                             {"frame": )" +
           std::to_string(frame) + R"(, "position": [1, 0, 0], "target": [1, 0, -1]}]})";
  };
  EXPECT_THAT([&] { CameraPath::parse(pathTo(INT_MAX), "long.json"); },
              ThrowsMessage<InputError>(
                  "long.json: keyframe 1: frame 2147483647 asks for 2147483648 frames, the limit "
                  "is 1000000"));
  EXPECT_EQ(CameraPath::parse(pathTo(kMaxCameraPathFrames - 1), "long.json").frameCount(),
            kMaxCameraPathFrames);
}

}  // namespace
}  // namespace vt
