// The two gates every command passes its files through: common/input_file.h (inputs are regular
// files, text under a size limit, names without NUL) and common/output_path.h (names from inputs
// stay inside their folder; outputs are neither inputs nor devices).

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "common/error.h"
#include "common/input_file.h"
#include "common/output_path.h"
#include "test_support.h"

namespace vt {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(InputFile, ReadsARegularFileWhole) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "a.json") << "{\"x\": 1}";
  EXPECT_EQ(readTextFile(dir / "a.json", "layout"), "{\"x\": 1}");
}

TEST(InputFile, RefusesATextLongerThanTheLimitBeforeReadingIt) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "big.json") << std::string(1001, ' ');
  EXPECT_THAT([&] { readTextFile(dir / "big.json", "layout file", 1000); },
              ThrowsMessage<InputError>(HasSubstr(
                  "big.json: reading layout file asks for 1001 bytes, the limit is 1000 bytes")));
}

TEST(InputFile, RefusesAFifoADeviceAFolderAndANameWithANul) {
  test::ScratchDirectory dir;
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  // Neither waits for a writer nor reads without end.
  EXPECT_THAT([&] { readTextFile(dir / "pipe", "camera path"); },
              ThrowsMessage<InputError>(
                  HasSubstr("pipe: cannot read camera path: it is a FIFO, not a regular file")));
  EXPECT_THAT([&] { readTextFile("/dev/zero", "mesh"); },
              ThrowsMessage<InputError>(
                  HasSubstr("/dev/zero: cannot read mesh: it is a character device")));
  EXPECT_THAT([&] { readTextFile(dir.path(), "mesh"); },
              ThrowsMessage<InputError>(HasSubstr("cannot read mesh: it is a folder")));
  EXPECT_THAT([&] { readTextFile(dir / "absent.obj", "mesh"); },
              ThrowsMessage<InputError>(
                  HasSubstr("absent.obj: cannot open mesh: No such file or directory")));
  std::ofstream(dir / "a.png") << "x";
  const std::filesystem::path cut((dir / "a.png").string() + std::string(1, '\0') + ".txt");
  EXPECT_THAT([&] { requireRegularFile(cut, "image"); },
              ThrowsMessage<InputError>(HasSubstr("a.png: the name of image holds a NUL")));
}

TEST(PathInside, KeepsRelativeNamesInsideAndRefusesTheOthersNamingTheSource) {
  test::ScratchDirectory dir;
  EXPECT_EQ(pathInside(dir.path(), "textures/a/b.tga", "p.pk3:textures/a/b.tga"),
            dir / "textures/a/b.tga");
  EXPECT_EQ(pathInside(dir.path(), "./x..y.tga", "s"), dir / "x..y.tga");
  for (const std::string name : {"../x.tga", "a/../../x.tga", "a/..", ".."})
    EXPECT_THAT([&] { pathInside(dir.path(), name, "p.pk3:" + name); },
                ThrowsMessage<InputError>(HasSubstr(
                    "p.pk3:" + name + ": the name '" + name + "' leads outside the folder " +
                    dir.path().filename().string() + "/: it has a '..' component")));
  EXPECT_THAT([&] { pathInside(dir.path(), "/etc/passwd", "p.pk3:/etc/passwd"); },
              ThrowsMessage<InputError>(HasSubstr("it is absolute")));
  EXPECT_THAT([&] { pathInside(dir.path(), "", "p.pk3:"); },
              ThrowsMessage<InputError>(HasSubstr("it is empty")));
  EXPECT_THAT([&] { pathInside(dir.path(), std::string("a\0b", 3), "s"); },
              ThrowsMessage<InputError>(HasSubstr("it holds a NUL character")));
}

TEST(PathInside, NeverFollowsASymbolicLinkOnTheWay) {
  test::ScratchDirectory dir;
  std::filesystem::create_directories(dir / "root");
  std::filesystem::create_directories(dir / "elsewhere");
  std::filesystem::create_directory_symlink(dir / "elsewhere", dir / "root" / "textures");
  std::filesystem::create_symlink(dir / "elsewhere" / "f", dir / "root" / "file.tga");
  EXPECT_THAT([&] { pathInside(dir / "root", "textures/a.tga", "s"); },
              ThrowsMessage<InputError>(HasSubstr("root/textures is a symbolic link")));
  EXPECT_THAT([&] { pathInside(dir / "root", "file.tga", "s"); },
              ThrowsMessage<InputError>(HasSubstr("root/file.tga is a symbolic link")));
}

TEST(OutputPath, RefusesAnOutputThatIsAnInputByDeviceAndInode) {
  test::ScratchDirectory dir;
  std::ofstream(dir / "in.png") << "x";
  std::filesystem::create_hard_link(dir / "in.png", dir / "same.png");
  std::filesystem::create_symlink(dir / "in.png", dir / "link.png");
  for (const char* output : {"in.png", "same.png", "link.png"})
    EXPECT_THAT(
        [&] {
          requireOutputFile(dir / output, {dir / "other.vt", dir / "in.png"});
        },
        ThrowsMessage<InputError>(HasSubstr("is the input " + (dir / "in.png").string())))
        << output;
  std::ofstream(dir / "old.png") << "y";
  EXPECT_NO_THROW(requireOutputFile(dir / "old.png", {dir / "in.png"}));  // replaced: fine
  EXPECT_NO_THROW(requireOutputFile(dir / "new.png", {dir / "in.png"}));
}

TEST(OutputPath, RefusesDevicesFifosAndFoldersWhereAFileGoesAndFilesWhereAFolderGoes) {
  test::ScratchDirectory dir;
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  EXPECT_THAT([&] { requireOutputFile("/dev/full", {}); },
              ThrowsMessage<InputError>(HasSubstr("/dev/full: is a character device")));
  EXPECT_THAT([&] { requireOutputFile(dir / "pipe", {}); },
              ThrowsMessage<InputError>(HasSubstr("is a FIFO, not a regular file")));
  EXPECT_THAT([&] { requireOutputFile(dir.path(), {}); },
              ThrowsMessage<InputError>(HasSubstr("is a folder, not a regular file")));
  EXPECT_THAT([&] { requireOutputFolder(dir / "pipe", {}); },
              ThrowsMessage<InputError>(HasSubstr("is a FIFO, not a folder")));
  std::filesystem::create_directories(dir / "out" / "sub");
  std::ofstream(dir / "out" / "sub" / "path.json") << "{}";
  EXPECT_THAT([&] { requireOutputFolder(dir / "out", {dir / "out" / "sub" / "path.json"}); },
              ThrowsMessage<InputError>(HasSubstr("holds the input")));
  EXPECT_NO_THROW(requireOutputFolder(dir / "out" / "sub" / "new", {dir / "out/sub/path.json"}));
}

}  // namespace
}  // namespace vt
