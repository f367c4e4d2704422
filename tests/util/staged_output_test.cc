#include "ramap/util/staged_output.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {
namespace fs = std::filesystem;

TEST(StagedOutput, WritesFileWhole) {
  test::TempDir dir;
  const std::string path = dir / "out.txt";
  WriteFileAtomically(path, [](std::ostream& out) { out << "hello\n"; });
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "hello");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(StagedOutput, FailedWriterLeavesNothingBehind) {
  test::TempDir dir;
  const std::string path = dir / "out.txt";
  EXPECT_THROW(WriteFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "partial";
                                     throw std::runtime_error("stage failed");
                                   }),
               std::runtime_error);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(StagedOutput, FolderReplacesOldOnlyOnCommit) {
  test::TempDir dir;
  const std::string final_path = dir / "model";
  fs::create_directory(final_path);
  std::ofstream(final_path + "/old.txt") << "old";
  {
    StagedPath staged(final_path);
    fs::create_directory(staged.path());
    std::ofstream(staged.path() + "/new.txt") << "new";
    // Not committed: the old folder stays and the staging folder goes.
  }
  EXPECT_TRUE(fs::exists(final_path + "/old.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  {
    StagedPath staged(final_path);
    fs::create_directory(staged.path());
    std::ofstream(staged.path() + "/new.txt") << "new";
    staged.Commit();
  }
  EXPECT_FALSE(fs::exists(final_path + "/old.txt"));
  EXPECT_TRUE(fs::exists(final_path + "/new.txt"));
}

}  // namespace
}  // namespace ramap
