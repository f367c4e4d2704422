#include "ramap/util/output_policy.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {
namespace fs = std::filesystem;

TEST(OutputPolicy, FileOutputRefusesFoldersAndInputs) {
  test::TempDir dir;
  fs::create_directories(dir / "model");
  std::ofstream(dir / "model/cameras.bin") << "x";
  std::ofstream(dir / "input.db") << "x";
  EXPECT_THROW(CheckFileOutput("--output_path", dir / "model", {}), InputError);
  EXPECT_THROW(CheckFileOutput("--output_path", dir.path() + "/.", {}), InputError);
  EXPECT_THROW(CheckFileOutput("--output_path", dir / "input.db", {dir / "input.db"}), InputError);
  // Another spelling of the same file is the same input.
  EXPECT_THROW(CheckFileOutput("--output_path", dir / "model/../input.db", {dir / "input.db"}),
               InputError);
  // A model file of an input model folder is an input too.
  EXPECT_THROW(CheckFileOutput("--output_path", dir / "model/cameras.bin", {dir / "model"}),
               InputError);
  EXPECT_NO_THROW(CheckFileOutput("--output_path", dir / "model/eval.json", {dir / "model"}));
  EXPECT_NO_THROW(CheckFileOutput("--output_path", dir / "new.txt", {dir / "input.db"}));
  test::ExpectInputError([&] { CheckFileOutput("--output_path", dir / "model", {}); },
                         {"--output_path"});
}

TEST(OutputPolicy, NewDatabaseNeverOverwrites) {
  test::TempDir dir;
  std::ofstream(dir / "existing.db") << "x";
  EXPECT_THROW(CheckNewDatabasePath("--database_path", dir / "existing.db", {}), InputError);
  EXPECT_NO_THROW(CheckNewDatabasePath("--database_path", dir / "new.db", {}));
}

TEST(OutputPolicy, FolderOutputRefusesFilesAndItsInput) {
  test::TempDir dir;
  std::ofstream(dir / "file") << "x";
  fs::create_directories(dir / "model");
  EXPECT_THROW(CheckFolderOutput("--output_path", dir / "file", {}), InputError);
  EXPECT_THROW(CheckFolderOutput("--output_path", dir / "model", {dir / "model"}), InputError);
  EXPECT_NO_THROW(CheckFolderOutput("--output_path", dir / "model", {dir / "file"}));
  EXPECT_NO_THROW(CheckFolderOutput("--output_path", dir / "new", {}));
}

TEST(OutputPolicy, ReplaceableModelAndMapperFolders) {
  test::TempDir dir;
  fs::create_directories(dir / "out/0");
  for (const char* name : {"cameras.bin", "images.bin", "points3D.bin", "trajectory_tum.txt"}) {
    std::ofstream(dir / ("out/0/" + std::string(name))) << "x";
  }
  std::ofstream(dir / "out/summary.json") << "{}";
  std::ofstream(dir / "out/0/project.ini") << "[General]";  // COLMAP's mapper writes one
  std::string foreign;
  EXPECT_TRUE(IsReplaceableModelFolder(dir / "out/0", &foreign));
  EXPECT_TRUE(IsReplaceableMapperOutput(dir / "out", &foreign));
  std::ofstream(dir / "out/0/notes.txt") << "mine";
  EXPECT_FALSE(IsReplaceableModelFolder(dir / "out/0", &foreign));
  EXPECT_EQ(foreign, dir / "out/0/notes.txt");
  EXPECT_FALSE(IsReplaceableMapperOutput(dir / "out", &foreign));
  EXPECT_EQ(foreign, dir / "out/0/notes.txt");
  fs::remove(dir / "out/0/notes.txt");
  fs::create_directories(dir / "out/photos");
  EXPECT_FALSE(IsReplaceableMapperOutput(dir / "out", &foreign));
  EXPECT_EQ(foreign, dir / "out/photos");
}

}  // namespace
}  // namespace ramap
