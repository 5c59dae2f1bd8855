// Retexturing a real Quake 3 map, q3dm6ish from OpenArena (scripts/fetch-openarena.sh fetches it;
// VT_OPENARENA_DIR names the folder of its .pk3 archives). Without the data the tests are skipped,
// except in CI (CI=true), where missing data is a failure.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "build/layout.h"
#include "build/texture_builder.h"
#include "format/virtual_texture_reader.h"
#include "openarena_data.h"
#include "retexture/retexture.h"
#include "retexture/retexture_outputs.h"
#include "scene/quake3_scene.h"
#include "test_support.h"

namespace vt {
namespace {

// An image decoded to 8-bit RGB, as `vt build` stores it at the finest level.
struct SourceImage {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> texels;
  glm::u8vec3 rgb(int64_t x, int64_t y) const {
    const uint8_t* t = &texels[(static_cast<size_t>(y) * width + x) * channels];
    return channels >= 3 ? glm::u8vec3(t[0], t[1], t[2]) : glm::u8vec3(t[0]);
  }
};

SourceImage decode(const std::filesystem::path& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // texels as stored, as `vt build` reads them
  auto input = OIIO::ImageInput::open(path.string(), &config);
  EXPECT_TRUE(input) << path;
  SourceImage image{input->spec().width, input->spec().height, input->spec().nchannels, {}};
  image.texels.resize(static_cast<size_t>(image.width) * image.height * image.channels);
  EXPECT_TRUE(
      input->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::UINT8, image.texels.data()));
  return image;
}

int64_t wrap(int64_t value, int64_t size) { return ((value % size) + size) % size; }

// The fraction of x is at least `margin` away from an integer.
bool clearOfTexelEdges(double x, double margin = 1e-3) {
  const double f = x - std::floor(x);
  return f > margin && f < 1.0 - margin;
}

class OpenArenaMap : public ::testing::Test {
 protected:
  static TexturedScene load(const std::filesystem::path& packages,
                            const std::filesystem::path& images) {
    return loadQuake3Map(PackageFiles::fromFolders({packages}), "q3dm6ish", images);
  }
  test::ScratchDirectory scratch_;
};

TEST_F(OpenArenaMap, Q3dm6ishLoadsEveryFaceWithItsTextures) {
  VT_REQUIRE_OPENARENA(folder);
  const TexturedScene scene = load(*folder, scratch_ / "images");
  EXPECT_EQ(scene.faces.size(), 907u);
  EXPECT_EQ(scene.textures.size(), 7u);
  EXPECT_EQ(scene.skipped.total(), 0u);
  EXPECT_EQ(scene.viewpoints.size(), 10u);  // its info_player_deathmatch entities
  for (const SourceTexture& texture : scene.textures) {
    EXPECT_FALSE(texture.missing) << texture.name;
    EXPECT_TRUE(std::filesystem::exists(texture.file)) << texture.name;
  }
}

// Every face gets an area inside the texture, no two areas overlap, every new coordinate lies in
// its face's area, and the built texture holds, at a face's new coordinates, the source texel of
// its old ones (finest level, texel-exact), for the thesis's layout and ours.
TEST_F(OpenArenaMap, Q3dm6ishRetexturedTextureHoldsEveryFacesSourceTexels) {
  VT_REQUIRE_OPENARENA(folder);
  const TexturedScene scene = load(*folder, scratch_ / "images");
  RetextureOptions options;
  options.measureCoherence = false;
  const RetextureResult result = retexture(scene, options);
  for (const MethodResult* method : {&result.baseline, &result.charts}) {
    const Retexturing& layout = method->layout;
    SCOPED_TRACE(layout.method);
    ASSERT_EQ(layout.faceArea.size(), scene.faces.size());
    const std::vector<TextureArea>& areas = layout.areas;
    for (size_t a = 0; a < areas.size(); ++a) {
      ASSERT_LE(areas[a].x + areas[a].width, layout.side);
      ASSERT_LE(areas[a].y + areas[a].height, layout.side);
      for (size_t b = a + 1; b < areas.size(); ++b) {
        const bool apart = areas[a].x + areas[a].width <= areas[b].x ||
                           areas[b].x + areas[b].width <= areas[a].x ||
                           areas[a].y + areas[a].height <= areas[b].y ||
                           areas[b].y + areas[b].height <= areas[a].y;
        ASSERT_TRUE(apart) << "areas " << a << " and " << b << " overlap";
      }
    }
    const std::vector<glm::vec2> uvs = retexturedUvs(scene, layout);
    const auto side = static_cast<double>(layout.side);
    for (size_t f = 0; f < scene.faces.size(); ++f) {
      const TexturedFace& face = scene.faces[f];
      const TextureArea& area = areas[layout.faceArea[f]];
      for (uint32_t i = face.firstIndex; i < face.firstIndex + face.indexCount; ++i) {
        const glm::dvec2 texel = glm::dvec2(uvs[scene.indices[i]]) * side;
        ASSERT_GE(texel.x, double(area.x) - 1e-3) << "face " << f;
        ASSERT_LE(texel.x, double(area.x + area.width) + 1e-3) << "face " << f;
        ASSERT_GE(texel.y, double(area.y) - 1e-3) << "face " << f;
        ASSERT_LE(texel.y, double(area.y + area.height) + 1e-3) << "face " << f;
      }
    }
  }

  // Build our layout and sample it.
  const std::filesystem::path layoutFile = scratch_ / "q3dm6ish.layout.json";
  writeRetextureLayout(layoutFile, scene, result.charts.layout, {});
  const std::filesystem::path textureFile = scratch_ / "q3dm6ish.vt";
  buildVirtualTexture(readLayout(layoutFile), textureFile, {.progress = false});
  const VirtualTextureReader reader(textureFile);
  const TextureDescription& d = reader.description();
  ASSERT_EQ(d.sideTexels(), result.charts.layout.side);
  std::map<uint64_t, std::vector<std::byte>> pages;
  const auto virtualTexel = [&](uint64_t x, uint64_t y) {
    const PageId page{static_cast<uint32_t>(x / d.pageSize), static_cast<uint32_t>(y / d.pageSize),
                      d.finestLevel()};
    auto [found, inserted] = pages.try_emplace(absoluteIndex(page));
    if (inserted) found->second = reader.readPage(page);
    const uint64_t tx = x % d.pageSize + d.border, ty = y % d.pageSize + d.border;
    const std::byte* t = &found->second[(ty * d.storedPageSide() + tx) * d.channels];
    return glm::u8vec3(uint8_t(t[0]), uint8_t(t[1]), uint8_t(t[2]));
  };
  std::vector<SourceImage> sources;
  for (const SourceTexture& texture : scene.textures) sources.push_back(decode(texture.file));

  const std::vector<glm::vec2> uvs = result.uvs;
  const auto side = static_cast<double>(result.charts.layout.side);
  uint64_t checked = 0;
  const glm::dvec3 samples[] = {
      {1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.2, 0.2, 0.6}};
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const TexturedFace& face = scene.faces[f];
    const SourceImage& source = sources[face.texture];
    for (uint32_t t = face.firstIndex; t < face.firstIndex + face.indexCount; t += 3) {
      const uint32_t v[3] = {scene.indices[t], scene.indices[t + 1], scene.indices[t + 2]};
      for (const glm::dvec3& b : samples) {
        const glm::dvec2 old = b.x * glm::dvec2(scene.uvs[v[0]]) +
                               b.y * glm::dvec2(scene.uvs[v[1]]) +
                               b.z * glm::dvec2(scene.uvs[v[2]]);
        const glm::dvec2 now =
            b.x * glm::dvec2(uvs[v[0]]) + b.y * glm::dvec2(uvs[v[1]]) + b.z * glm::dvec2(uvs[v[2]]);
        const glm::dvec2 u = old * glm::dvec2(source.width, source.height), w = now * side;
        if (!clearOfTexelEdges(u.x) || !clearOfTexelEdges(u.y) || !clearOfTexelEdges(w.x) ||
            !clearOfTexelEdges(w.y))
          continue;
        const glm::u8vec3 expected =
            source.rgb(wrap(static_cast<int64_t>(std::floor(u.x)), source.width),
                       wrap(static_cast<int64_t>(std::floor(u.y)), source.height));
        const glm::u8vec3 got = virtualTexel(static_cast<uint64_t>(std::floor(w.x)),
                                             static_cast<uint64_t>(std::floor(w.y)));
        ASSERT_EQ(expected, got) << "face " << f << " at old uv (" << old.x << ", " << old.y << ")";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 9000u);  // of 4 * 2621 samples, the few on texel edges skipped
}

TEST_F(OpenArenaMap, OursWastesLessThanTheThesisLayout) {
  VT_REQUIRE_OPENARENA(folder);
  const TexturedScene scene = load(*folder, scratch_ / "images");
  RetextureOptions options;
  options.coherence.width = 320;
  options.coherence.height = 180;
  const RetextureResult result = retexture(scene, options);
  EXPECT_LT(result.charts.layout.side, result.baseline.layout.side);
  EXPECT_LT(result.charts.quality.finestPages * 2, result.baseline.quality.finestPages);
  EXPECT_GT(result.charts.quality.referencedFraction,
            2.0 * result.baseline.quality.referencedFraction);
  ASSERT_TRUE(result.charts.coherence && result.baseline.coherence);
  EXPECT_EQ(result.charts.coherence->views, 40u);
  EXPECT_GT(result.charts.coherence->pagesPer1000Pixels, 0.0);
}

}  // namespace
}  // namespace vt
