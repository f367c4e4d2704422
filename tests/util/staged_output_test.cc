#include "ramap/util/staged_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "ramap/util/error.h"
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

TEST(StagedOutput, NeverReplacesAFolderThatHoldsSomething) {
  test::TempDir dir;
  const std::string final_path = dir / "model";
  fs::create_directory(final_path);
  std::ofstream(final_path + "/old.txt") << "old";
  {
    StagedPath staged(final_path);
    fs::create_directory(staged.path());
    std::ofstream(staged.path() + "/new.txt") << "new";
    EXPECT_THROW(staged.Commit(), InputError);
  }
  // The user's folder stays as it was and the staging folder is gone.
  EXPECT_TRUE(fs::exists(final_path + "/old.txt"));
  EXPECT_FALSE(fs::exists(final_path + "/new.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
  // A file is never put in place of a folder either.
  EXPECT_THROW(WriteFileAtomically(final_path, [](std::ostream& out) { out << "x"; }), InputError);
  EXPECT_TRUE(fs::exists(final_path + "/old.txt"));
}

TEST(StagedOutput, NewFolderAppearsOnCommit) {
  test::TempDir dir;
  const std::string final_path = dir / "model";
  {
    StagedPath staged(final_path);
    fs::create_directory(staged.path());
    std::ofstream(staged.path() + "/new.txt") << "new";
    // Not committed: nothing appears.
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
  StagedPath staged(final_path);
  fs::create_directory(staged.path());
  std::ofstream(staged.path() + "/new.txt") << "new";
  staged.Commit();
  EXPECT_TRUE(fs::exists(final_path + "/new.txt"));
}

TEST(StagedOutput, FinalPathOfAStagedPathIsTheCallersPath) {
  test::TempDir dir;
  StagedPath file(dir / "edges.txt");
  EXPECT_EQ(FinalPathOf(file.path()), dir / "edges.txt");
  StagedPath folder(dir / "sparse/");
  EXPECT_EQ(FinalPathOf(folder.path() + "/0/images.bin"), dir / "sparse");
  EXPECT_EQ(FinalPathOf(dir / "model/images.bin"), dir / "model/images.bin");
}

TEST(StagedOutput, InterruptRemovesStagedAndCreatedOutputs) {
  test::TempDir dir;
  StagedPath staged(dir / "model");
  fs::create_directory(staged.path());
  std::ofstream(staged.path() + "/part.bin") << "half";
  CreatedOutput created(dir / "database.db");
  std::ofstream(dir / "database.db") << "half";
  std::ofstream(dir / "mine.txt") << "the user's";
  CreatedOutput existed(dir / "mine.txt");  // existed before: never removed
  RemoveLiveOutputs();
  EXPECT_FALSE(fs::exists(staged.path()));
  EXPECT_FALSE(fs::exists(dir / "database.db"));
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
}

TEST(StagedOutput, CreatedOutputKeptOrRemoved) {
  test::TempDir dir;
  {
    CreatedOutput created(dir / "out");
    fs::create_directories(dir / "out/sub");
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  {
    CreatedOutput created(dir / "out");
    fs::create_directories(dir / "out/sub");
    created.Keep();
  }
  EXPECT_TRUE(fs::exists(dir / "out/sub"));
}

}  // namespace
}  // namespace ramap
