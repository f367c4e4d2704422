// Relative pose and rotation files: lossless round trip, and bad lines named by file and line.
#include "ramap/io/relative_pose_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(RelativePoseFile, RoundTripIsLossless) {
  test::TempDir dir;
  std::vector<RelativePoseRecord> records(2);
  records[0] = {"a.png",
                "b.png",
                Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized(),
                Eigen::Vector3d(0.6, -0.8, 0.0),
                123,
                0};
  records[1] = {"b.png",
                "c.png",
                Eigen::Quaterniond(Eigen::AngleAxisd(1e-9, Eigen::Vector3d::UnitY())),
                Eigen::Vector3d::Zero(),
                15,
                1};
  WriteRelativePoses(records, dir / "edges.txt");
  const std::vector<RelativePoseRecord> back = ReadRelativePoses(dir / "edges.txt");
  ASSERT_EQ(back.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back[k].image_name1, records[k].image_name1);
    EXPECT_EQ(back[k].image_name2, records[k].image_name2);
    EXPECT_EQ(back[k].rotation.coeffs(), records[k].rotation.coeffs());
    EXPECT_EQ(back[k].translation, records[k].translation);
    EXPECT_EQ(back[k].num_inliers, records[k].num_inliers);
    EXPECT_EQ(back[k].flags, records[k].flags);
  }
}

TEST(RelativePoseFile, BadLinesNameFileAndLine) {
  test::TempDir dir;
  const std::string path = dir / "edges.txt";
  const std::string good = "a b 1 0 0 0 1 0 0 20 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"# only a comment\n", "holds no relative pose"},
      {good + "a c 1 0 0 0 1 0\n", "line 2: expected NAME1 NAME2"},
      {good + "a c 1 0 0 0 1 0 0 20 0 extra\n", "line 2: unexpected 'extra'"},
      {good + "a c nan 0 0 0 1 0 0 20 0\n", "line 2: a value is not finite"},
      {good + "a c 2 0 0 0 1 0 0 20 0\n", "line 2: the quaternion is not of unit norm"},
      {good + "a a 1 0 0 0 1 0 0 20 0\n", "line 2: pairs an image (a) with itself"},
      {good + "a c 1 0 0 0 1 0 0 -3 0\n",
       "line 2: num_inliers and flags must be whole numbers >= 0"},
      {good + "a c 1 0 0 0 1 0 0 2.5 0\n",
       "line 2: num_inliers and flags must be whole numbers >= 0"},
      {good + "a c 1 0 0 x 1 0 0 20 0\n", "line 2: expected NAME1 NAME2"},
  };
  for (const auto& [text, message] : cases) {
    WriteText(path, text);
    SCOPED_TRACE(text);
    test::ExpectInputError([&] { ReadRelativePoses(path); }, {path, message});
  }
  EXPECT_THROW(ReadRelativePoses(dir / "missing.txt"), InputError);
}

TEST(RelativePoseFile, FailedWriteLeavesNothing) {
  test::TempDir dir;
  const std::string path = dir / "no_such_folder/rotations.txt";
  EXPECT_THROW(WriteRotations({{"a.png", Eigen::Quaterniond::Identity()}}, path), InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(WriteRotations({{"frame 1.png", Eigen::Quaterniond::Identity()}}, dir / "r.txt"),
               InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "r.txt"));
}

}  // namespace
}  // namespace ramap
