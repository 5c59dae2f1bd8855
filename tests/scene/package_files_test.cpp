// PackageFiles over zip archives generated here with libzip, and the TextureResolver over them.

#include "scene/package_files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <utility>

#include "common/error.h"
#include "scene/quake3_fixtures.h"
#include "scene/texture_resolver.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

using test::writeZip;

std::string text(const std::vector<uint8_t>& bytes) {
  return std::string(bytes.begin(), bytes.end());
}

// The archive's constructor (or read) fails with an InputError whose message holds every part.
template <typename F>
void expectInputError(F&& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    for (const auto& part : parts) EXPECT_THAT(error.what(), HasSubstr(part));
  }
}

TEST(PackageFiles, LaterArchiveOverridesEarlierWithoutRegardToCase) {
  test::ScratchDirectory scratch;
  writeZip(scratch / "a.pk3", {{"textures/Base/Wall.tga", "old wall"}, {"only/in/a.txt", "a"}});
  writeZip(scratch / "b.pk3", {{"TEXTURES/base/wall.TGA", "new wall"}, {"only/in/b.txt", "b"}});

  PackageFiles files({scratch / "a.pk3", scratch / "b.pk3"});
  EXPECT_EQ(files.find("textures/base/wall.tga"), "TEXTURES/base/wall.TGA");
  EXPECT_EQ(text(files.read("Textures/Base/Wall.tga")), "new wall");
  EXPECT_EQ(files.describe("textures/base/wall.tga"),
            (scratch / "b.pk3").string() + ":TEXTURES/base/wall.TGA");
  // Names only one archive holds stay visible.
  EXPECT_EQ(text(files.read("only/in/a.txt")), "a");
  EXPECT_EQ(text(files.read("only/in/b.txt")), "b");

  // The other load order, read through a moved-to object.
  PackageFiles reversed({scratch / "b.pk3", scratch / "a.pk3"});
  PackageFiles moved(std::move(reversed));
  EXPECT_EQ(moved.find("textures/base/wall.tga"), "textures/Base/Wall.tga");
  EXPECT_EQ(text(moved.read("textures/base/wall.tga")), "old wall");
}

TEST(PackageFiles, FromFoldersSortsEachFoldersArchivesByNameIgnoringCase) {
  test::ScratchDirectory scratch;
  std::filesystem::create_directories(scratch / "base");
  std::filesystem::create_directories(scratch / "mod");
  // Byte order would load "Zeta" before "alpha"; the game loads alpha first, so Zeta wins.
  writeZip(scratch / "base/alpha.pk3", {{"x.txt", "alpha"}, {"y.txt", "alpha"}});
  writeZip(scratch / "base/Zeta.PK3", {{"x.txt", "zeta"}, {"y.txt", "zeta"}});
  writeZip(scratch / "base/ignored.zip", {{"x.txt", "not a pk3"}});
  // A later folder overrides the earlier one whatever its archives are called.
  writeZip(scratch / "mod/aaa.pk3", {{"y.txt", "mod"}});

  const PackageFiles files = PackageFiles::fromFolders({scratch / "base", scratch / "mod"});
  EXPECT_EQ(text(files.read("x.txt")), "zeta");
  EXPECT_EQ(text(files.read("y.txt")), "mod");

  expectInputError([&] { PackageFiles::fromFolders({scratch / "nowhere"}); }, {"nowhere"});
}

TEST(PackageFiles, FindIgnoresCaseAndSeparatorAndFolders) {
  test::ScratchDirectory scratch;
  writeZip(scratch / "pak0.pk3",
           {{"textures/", ""}, {"textures/base/", ""}, {"textures/base/Floor.jpg", "floor"}});
  const PackageFiles files({scratch / "pak0.pk3"});
  EXPECT_EQ(files.find("TEXTURES/BASE/FLOOR.JPG"), "textures/base/Floor.jpg");
  EXPECT_EQ(files.find("textures\\base\\floor.jpg"), "textures/base/Floor.jpg");
  EXPECT_EQ(files.find("textures/base/"), std::nullopt);
  EXPECT_EQ(files.find("textures/base"), std::nullopt);
  EXPECT_EQ(files.find("textures/base/floor.tga"), std::nullopt);
  EXPECT_THAT(files.list("", ""), ElementsAre("textures/base/Floor.jpg"));
}

TEST(PackageFiles, ListsByPrefixAndSuffixSortedByLowerCaseName) {
  test::ScratchDirectory scratch;
  writeZip(scratch / "a.pk3", {{"scripts/b.shader", ""},
                               {"scripts/readme.txt", ""},
                               {"scripts/sub/", ""},
                               {"textures/c.shader", ""},
                               {"scriptsx/d.shader", ""}});
  writeZip(scratch / "b.pk3", {{"Scripts/A.SHADER", ""}, {"scripts/C.Shader", ""}});
  const PackageFiles files({scratch / "a.pk3", scratch / "b.pk3"});
  EXPECT_THAT(files.list("scripts/", ".shader"),
              ElementsAre("Scripts/A.SHADER", "scripts/b.shader", "scripts/C.Shader"));
  EXPECT_THAT(files.list("SCRIPTS/", ".TXT"), ElementsAre("scripts/readme.txt"));
  EXPECT_EQ(files.list("", "").size(), 6u);  // the folder entry is not a file
  EXPECT_TRUE(files.list("models/", "").empty());
}

TEST(PackageFiles, RejectsFilesThatAreNotZipArchivesNamingThem) {
  test::ScratchDirectory scratch;
  std::mt19937 random(7);
  std::vector<std::byte> junk(4096);
  for (auto& b : junk) b = std::byte(random() & 0xff);
  test::writeBytes(scratch / "junk.pk3", junk);

  std::string contents;
  for (int i = 0; i < 2000; ++i) contents += std::to_string(random()) + "\n";
  writeZip(scratch / "whole.pk3", {{"a.txt", contents}, {"b.txt", contents}});
  std::vector<std::byte> whole = test::readBytes(scratch / "whole.pk3");
  whole.resize(whole.size() / 2);
  test::writeBytes(scratch / "truncated.pk3", whole);

  writeZip(scratch / "good.pk3", {{"a.txt", "a"}});
  for (const char* name : {"junk.pk3", "truncated.pk3", "absent.pk3"}) {
    SCOPED_TRACE(name);
    try {
      PackageFiles files({scratch / "good.pk3", scratch / name});
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), scratch / name);
      EXPECT_THAT(error.what(), AllOf(HasSubstr(name), HasSubstr("not a readable zip archive")));
    }
  }
}

TEST(PackageFiles, RejectsMissingAndDamagedEntriesNamingArchiveAndEntry) {
  test::ScratchDirectory scratch;
  std::mt19937 random(11);
  std::string contents;
  for (int i = 0; i < 4000; ++i) contents += std::to_string(random() % 1000) + " ";
  writeZip(scratch / "pak0.pk3", {{"textures/damaged.tga", contents}});

  // Flip bytes inside the entry's deflated data, which starts after the local header (30 bytes,
  // then the name and the extra field, whose lengths are at offsets 26 and 28).
  std::vector<std::byte> bytes = test::readBytes(scratch / "pak0.pk3");
  const size_t data = 30 + std::to_integer<size_t>(bytes[26]) +
                      256 * std::to_integer<size_t>(bytes[27]) +
                      std::to_integer<size_t>(bytes[28]) + 256 * std::to_integer<size_t>(bytes[29]);
  for (size_t i = data + 100; i < data + 140; ++i) bytes[i] ^= std::byte{0x5a};
  test::writeBytes(scratch / "pak0.pk3", bytes);

  const PackageFiles files({scratch / "pak0.pk3"});
  ASSERT_EQ(files.find("textures/damaged.tga"), "textures/damaged.tga");
  expectInputError([&] { files.read("textures/damaged.tga"); },
                   {(scratch / "pak0.pk3").string(), "textures/damaged.tga"});
  expectInputError([&] { files.read("textures/missing.tga"); },
                   {"textures/missing.tga", (scratch / "pak0.pk3").string()});
  EXPECT_EQ(files.describe("textures/missing.tga"), "textures/missing.tga");
}

// A game folder for the resolver: images in one archive, scripts in another.
class TextureResolverTest : public ::testing::Test {
 protected:
  void SetUp() override {
    writeZip(scratch_ / "pak0.pk3", {{"textures/base/wall.tga", "wall tga"},
                                     {"textures/base/wall.jpg", "wall jpg"},
                                     {"textures/base/Floor.JPG", "floor jpg"},
                                     {"textures/sfx/flame1.jpg", "flame jpg"},
                                     {"textures/sfx/glass_ed.tga", "glass editor image"},
                                     {"textures/dup/first.tga", "first"},
                                     {"textures/dup/second.tga", "second"}});
    writeZip(scratch_ / "pak1.pk3", {{"scripts/a.shader", R"(
textures/sfx/flame
{
  qer_editorimage textures/sfx/flame_ed.tga
  { map $lightmap }
  { map textures/sfx/flame1.tga }
}
textures/sfx/glass { qer_editorimage textures/sfx/glass_ed.tga
  { map $lightmap } }
textures/sfx/ghost { qer_editorimage textures/sfx/glass_ed
  { map textures/sfx/missing.tga } }
textures/sfx/void { { map $whiteimage } }
textures/base/wall { { map textures/sfx/flame1.tga } }
textures/dup/x { { map textures/dup/first.tga } }
)"},
                                     {"scripts/B.shader", R"(
TEXTURES/DUP/X { { map textures/dup/second.tga } }
)"}});
  }

  test::ScratchDirectory scratch_;
};

TEST_F(TextureResolverTest, ResolvesImagesTgaBeforeJpgWhateverTheExtension) {
  const PackageFiles files({scratch_ / "pak0.pk3", scratch_ / "pak1.pk3"});
  const TextureResolver resolver(files);
  using Via = ResolvedTexture::Via;
  const auto expect = [&](std::string_view name, const std::string& file, Via via) {
    SCOPED_TRACE(name);
    const auto resolved = resolver.resolve(name);
    ASSERT_TRUE(resolved.has_value());
    EXPECT_EQ(resolved->file, file);
    EXPECT_EQ(resolved->via, via);
  };
  // An image is preferred to a shader of the same name.
  expect("textures/base/wall", "textures/base/wall.tga", Via::kImage);
  expect("textures/base/wall.jpg", "textures/base/wall.tga", Via::kImage);
  expect("textures/base/floor", "textures/base/Floor.JPG", Via::kImage);
  expect("Textures/Base/Floor.tga", "textures/base/Floor.JPG", Via::kImage);
  expect("textures/base/floor.png", "textures/base/Floor.JPG", Via::kImage);
}

TEST_F(TextureResolverTest, ResolvesShaderNamesThroughTheirScripts) {
  const PackageFiles files({scratch_ / "pak0.pk3", scratch_ / "pak1.pk3"});
  const TextureResolver resolver(files);
  using Via = ResolvedTexture::Via;
  // The stage names flame1.tga; only flame1.jpg exists.
  const auto flame = resolver.resolve("TEXTURES/SFX/Flame");
  ASSERT_TRUE(flame.has_value());
  EXPECT_EQ(flame->file, "textures/sfx/flame1.jpg");
  EXPECT_EQ(flame->via, Via::kShaderStage);

  const auto glass = resolver.resolve("textures/sfx/glass");
  ASSERT_TRUE(glass.has_value());
  EXPECT_EQ(glass->file, "textures/sfx/glass_ed.tga");
  EXPECT_EQ(glass->via, Via::kEditorImage);

  // A stage image no archive holds falls back to the editor image (named without extension).
  const auto ghost = resolver.resolve("textures/sfx/ghost");
  ASSERT_TRUE(ghost.has_value());
  EXPECT_EQ(ghost->file, "textures/sfx/glass_ed.tga");
  EXPECT_EQ(ghost->via, Via::kEditorImage);

  // scripts/B.shader comes after scripts/a.shader in name order, whatever the case: it wins.
  const auto duplicate = resolver.resolve("textures/dup/x");
  ASSERT_TRUE(duplicate.has_value());
  EXPECT_EQ(duplicate->file, "textures/dup/second.tga");

  EXPECT_EQ(resolver.resolve("textures/sfx/void"), std::nullopt);
  EXPECT_EQ(resolver.resolve("textures/nothing/here"), std::nullopt);
}

TEST_F(TextureResolverTest, RejectsABrokenScriptNamingArchiveScriptAndLine) {
  writeZip(scratch_ / "pak2.pk3", {{"scripts/broken.shader", "textures/a/b\n{\n { map x.tga }\n"}});
  const PackageFiles files({scratch_ / "pak0.pk3", scratch_ / "pak1.pk3", scratch_ / "pak2.pk3"});
  expectInputError([&] { TextureResolver resolver(files); },
                   {"pak2.pk3", "scripts/broken.shader", "line 2"});
}

}  // namespace
}  // namespace vt
