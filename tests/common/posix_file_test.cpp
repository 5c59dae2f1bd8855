#include "common/posix_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli/run_command.h"
#include "common/error.h"
#include "test_support.h"

namespace vt {
namespace {

size_t entries(const std::filesystem::path& dir) {
  return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                           std::filesystem::directory_iterator()));
}

TEST(TemporaryFile, CommitReplacesTheDestinationAtOnce) {
  test::ScratchDirectory dir;
  test::writeBytes(dir / "out.bin", {std::byte{1}, std::byte{2}});
  {
    TemporaryFile temporary(dir / "out.bin");
    const std::byte data[3] = {std::byte{7}, std::byte{8}, std::byte{9}};
    temporary.file().writeAll(0, data);
    // Until commit the destination keeps its old content.
    EXPECT_EQ(test::readBytes(dir / "out.bin").size(), 2u);
    EXPECT_EQ(temporary.file().path().extension(), ".bin");
    temporary.commit();
  }
  EXPECT_EQ(test::readBytes(dir / "out.bin"),
            (std::vector<std::byte>{std::byte{7}, std::byte{8}, std::byte{9}}));
  EXPECT_EQ(entries(dir.path()), 1u);
}

TEST(TemporaryFile, AbandonedFileIsRemoved) {
  test::ScratchDirectory dir;
  {
    TemporaryFile temporary(dir / "out.bin");
    EXPECT_EQ(entries(dir.path()), 1u);
  }
  EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(TemporaryFile, MissingFolderIsAnInputError) {
  test::ScratchDirectory dir;
  EXPECT_THAT([&] { TemporaryFile temporary(dir / "no" / "out.bin"); },
              ::testing::ThrowsMessage<InputError>(
                  ::testing::HasSubstr("cannot create a temporary file in")));
}

TEST(TemporaryFolder, CommitReplacesAPreviousOutputWhole) {
  test::ScratchDirectory dir;
  std::filesystem::create_directories(dir / "out");
  writeFileAtomically(dir / "out" / "summary.json", "old");
  writeFileAtomically(dir / "out" / "only-old.csv", "old");
  {
    TemporaryFolder staging(dir / "out", "summary.json");
    EXPECT_EQ(staging.path().parent_path(), std::filesystem::absolute(dir.path()));
    EXPECT_THAT(staging.path().filename().string(), ::testing::StartsWith(".out.tmp-"));
    writeFileAtomically(staging.path() / "summary.json", "new");
    // Until the commit, readers see the previous output whole.
    EXPECT_EQ(test::slurp(dir / "out" / "summary.json"), "old");
    staging.commit();
  }
  EXPECT_EQ(test::slurp(dir / "out" / "summary.json"), "new");
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "only-old.csv"));
  EXPECT_EQ(entries(dir.path()), 1u);  // the previous folder is gone, nothing left beside
}

TEST(TemporaryFolder, AbandonedFolderIsRemovedAndTheDestinationKept) {
  test::ScratchDirectory dir;
  {
    TemporaryFolder staging(dir / "out", "golden.json");
    writeFileAtomically(staging.path() / "golden.json", "partial");
  }
  EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(TemporaryFolder, RefusesFoldersThatAreNotAPreviousOutput) {
  test::ScratchDirectory dir;
  std::filesystem::create_directories(dir / "home");
  writeFileAtomically(dir / "home" / "thesis.tex", "precious");
  try {
    TemporaryFolder staging(dir / "home", "summary.json");
    ADD_FAILURE() << "accepted a folder of other files";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("holds files but no summary.json"));
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "home" / "thesis.tex"));
  writeFileAtomically(dir / "file", "x");
  EXPECT_THAT([&] { TemporaryFolder::requireReplaceable(dir / "file", "summary.json"); },
              ::testing::ThrowsMessage<InputError>((dir / "file").string() +
                                                   ": is a file, not a folder for the output"));
  std::filesystem::create_directories(dir / "empty");
  TemporaryFolder::requireReplaceable(dir / "empty", "summary.json");  // an empty folder is fine
}

TEST(PosixFile, ShortReadIsAnError) {
  test::ScratchDirectory dir;
  test::writeBytes(dir / "f", std::vector<std::byte>(10));
  const PosixFile file = PosixFile::openForReading(dir / "f");
  std::vector<std::byte> buffer(8);
  EXPECT_NO_THROW(file.readExact(2, buffer));
  EXPECT_THAT([&] { file.readExact(4, buffer); },
              ::testing::ThrowsMessage<InputError>(
                  ::testing::HasSubstr("unexpected end of file at byte 10")));
}

}  // namespace
}  // namespace vt
