// OutputFile: parent folders created, whole files or nothing, no stray temporaries.
#include "format/output_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/test_util.h"

namespace meshvid {
namespace {

namespace fs = std::filesystem;

std::size_t EntriesIn(const std::string& folder) {
  std::size_t count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++count;
  return count;
}

TEST(OutputFileTest, CreatesMissingParentFolders) {
  testing::TempDir dir;
  const std::string path = dir.File("x/y/z/out.bin");
  ASSERT_TRUE(WriteFileAtomically(path, "bytes").ok());
  EXPECT_EQ(testing::ReadFile(path), "bytes");
  EXPECT_EQ(EntriesIn(dir.File("x/y/z")), 1u);
}

TEST(OutputFileTest, AnAbandonedWriteLeavesTheOldFileAndNoTemporary) {
  testing::TempDir dir;
  const std::string path = dir.File("out.txt");
  ASSERT_TRUE(WriteFileAtomically(path, "old").ok());
  {
    StatusOr<std::unique_ptr<OutputFile>> file = OutputFile::Open(path);
    ASSERT_TRUE(file.ok()) << file.status().message();
    (*file)->stream() << "new but never committed";
    EXPECT_EQ(testing::ReadFile(path), "old");  // the target is untouched while writing
  }
  EXPECT_EQ(testing::ReadFile(path), "old");
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(OutputFileTest, CommitReplacesTheTarget) {
  testing::TempDir dir;
  const std::string path = dir.File("out.txt");
  ASSERT_TRUE(WriteFileAtomically(path, "old").ok());
  StatusOr<std::unique_ptr<OutputFile>> file = OutputFile::Open(path);
  ASSERT_TRUE(file.ok());
  (*file)->stream() << "new";
  ASSERT_TRUE((*file)->Commit().ok());
  EXPECT_EQ(testing::ReadFile(path), "new");
  EXPECT_FALSE((*file)->Commit().ok());  // once only
  EXPECT_EQ(EntriesIn(dir.path()), 1u);
}

TEST(OutputFileTest, RefusesAFolderOrAFileInTheWay) {
  testing::TempDir dir;
  fs::create_directories(dir.File("folder"));
  StatusOr<std::unique_ptr<OutputFile>> folder = OutputFile::Open(dir.File("folder"));
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(folder.status().message().find("is a folder"), std::string::npos);

  testing::WriteFile(dir.File("file"), "x");
  const Status blocked = WriteFileAtomically(dir.File("file/out.txt"), "y");
  EXPECT_EQ(blocked.code(), StatusCode::kIoError);
  EXPECT_NE(blocked.message().find("cannot create the folder"), std::string::npos)
      << blocked.message();
  EXPECT_EQ(OutputFile::Open("").status().code(), StatusCode::kInvalidArgument);
}

// `-o /dev/null` writes into the device: renaming a temporary onto it would replace the
// device with a plain file (for a user allowed to write in /dev).
TEST(OutputFileTest, ADeviceIsWrittenInPlaceNotReplaced) {
  const std::string device = "/dev/null";
  if (!std::filesystem::is_character_file(device)) GTEST_SKIP() << device << " is no device here";
  StatusOr<std::unique_ptr<OutputFile>> file = OutputFile::Open(device);
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_TRUE((*file)->in_place());
  (*file)->stream() << "bytes";
  EXPECT_TRUE((*file)->Commit().ok());
  EXPECT_TRUE(std::filesystem::is_character_file(device));
  EXPECT_TRUE(WriteFileAtomically(device, "more").ok());
  EXPECT_TRUE(std::filesystem::is_character_file(device));
}

}  // namespace
}  // namespace meshvid
