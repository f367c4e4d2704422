// `ramap synthesize`: writes a database, a ground-truth model and a TUM trajectory that read back.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "test_support.h"

namespace ramap {
namespace {

size_t CountLines(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  size_t count = 0;
  while (std::getline(file, line)) count += !line.empty() && line[0] != '#';
  return count;
}

TEST(SyntheticCommand, WritesDatabaseModelAndTrajectory) {
  test::TempDir dir;
  const test::CommandResult result = test::RunCommand(
      "'" + test::RamapBinary() + "' synthesize --output_path '" + (dir / "out") +
      "' --Synthetic.num_images 12 --Synthetic.num_points 500 --Synthetic.path loop"
      " --Synthetic.num_outlier_pairs 1 --Synthetic.seed 5");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const FeatureDatabase database = ReadColmapDatabase(dir / "out/database.db");
  EXPECT_EQ(database.images.size(), 12u);
  EXPECT_FALSE(database.two_view_geometries.empty());
  const Reconstruction truth = ReadColmapModel(dir / "out/ground_truth");
  EXPECT_EQ(truth.images.size(), 12u);
  EXPECT_GT(truth.points3D.size(), 100u);
  EXPECT_EQ(CountLines(dir / "out/ground_truth.txt"), 12u);
}

TEST(SyntheticCommand, KittiTrajectoryFile) {
  RAMAP_REQUIRE_SHARED_DATA(path, "gt_trajectories/kitti_odometry_poses/07.txt");
  test::TempDir dir;
  const test::CommandResult result =
      test::RunCommand("'" + test::RamapBinary() + "' synthesize --output_path '" + (dir / "out") +
                       "' --Synthetic.trajectory_path '" + path + "' --Synthetic.num_images 40" +
                       " --Synthetic.num_points 1500");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const Reconstruction truth = ReadColmapModel(dir / "out/ground_truth");
  EXPECT_EQ(truth.images.size(), 40u);
}

TEST(SyntheticCommand, BadOptionsFailWithAMessage) {
  test::TempDir dir;
  const test::CommandResult result =
      test::RunCommand("'" + test::RamapBinary() + "' synthesize --output_path '" + (dir / "out") +
                       "' --Synthetic.outlier_ratio 1.5");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("Synthetic.outlier_ratio"), std::string::npos) << result.output;
  const test::CommandResult model =
      test::RunCommand("'" + test::RamapBinary() + "' synthesize --output_path '" + (dir / "out") +
                       "' --Synthetic.camera_model NOPE");
  EXPECT_EQ(model.exit_code, 2);
  EXPECT_NE(model.output.find("NOPE"), std::string::npos) << model.output;
}

}  // namespace
}  // namespace ramap
