// `ramap relative_poses` and `ramap rotation_averager` end to end on a noise-free synthetic scene:
// exact relative and absolute rotations, and clear failures on unusable input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/relative_pose_file.h"
#include "test_support.h"

namespace ramap {
namespace {

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.inverse() * b).angle() * 180.0 / M_PI;
}

// A noise-free 40-frame loop; returns the true cam_from_world rotation of each image by name.
std::map<std::string, Eigen::Quaterniond> MakeScene(const test::TempDir& dir) {
  const test::CommandResult result = test::RunCommand(
      test::RamapCommand() + "synthesize --output_path '" + (dir / "scene") +
      "' --Synthetic.path loop --Synthetic.num_images 40 --Synthetic.num_points 1500"
      " --Synthetic.pixel_noise 0 --Synthetic.outlier_ratio 0 --Synthetic.seed 3");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::map<std::string, Eigen::Quaterniond> truth;
  for (const auto& [id, image] : ReadColmapModel(dir / "scene/ground_truth").images) {
    truth[image.name] = image.cam_from_world.rotation;
  }
  return truth;
}

std::map<std::string, Eigen::Quaterniond> ReadRotationFile(const std::string& path) {
  std::map<std::string, Eigen::Quaterniond> rotations;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name;
    double w, x, y, z;
    fields >> name >> w >> x >> y >> z;
    rotations[name] = Eigen::Quaterniond(w, x, y, z);
  }
  return rotations;
}

// Largest rotation error after fixing the gauge on the first image.
double MaxAlignedErrorDeg(const std::map<std::string, Eigen::Quaterniond>& estimate,
                          const std::map<std::string, Eigen::Quaterniond>& truth) {
  const std::string& first = estimate.begin()->first;
  const Eigen::Quaterniond gauge = estimate.at(first).inverse() * truth.at(first);
  double worst = 0;
  for (const auto& [name, R] : estimate)
    worst = std::max(worst, AngleDeg(R * gauge, truth.at(name)));
  return worst;
}

TEST(RotationCommands, NoiseFreeSceneIsRecoveredExactly) {
  test::TempDir dir;
  const auto truth = MakeScene(dir);
  const std::string db = dir / "scene/database.db";

  const test::CommandResult edges =
      test::RunCommand(test::RamapCommand() + "relative_poses --database_path '" + db +
                       "' --output_path '" + (dir / "edges.txt") + "'");
  ASSERT_EQ(edges.exit_code, 0) << edges.output;
  // Piped, the progress is one closing line for the stage.
  EXPECT_NE(edges.output.find("[ramap] relative poses: " +
                              std::to_string(ReadColmapDatabase(db).two_view_geometries.size()) +
                              " pairs in "),
            std::string::npos)
      << edges.output;
  const std::vector<RelativePoseRecord> records = ReadRelativePoses(dir / "edges.txt");
  EXPECT_EQ(records.size(), ReadColmapDatabase(db).two_view_geometries.size());
  double worst_edge = 0;
  for (const RelativePoseRecord& r : records) {
    const Eigen::Quaterniond expected = truth.at(r.image_name2) * truth.at(r.image_name1).inverse();
    worst_edge = std::max(worst_edge, AngleDeg(r.rotation, expected));
  }
  // Keypoints are float32 in a COLMAP database: ~4e-5 px of rounding at 640 px, ~5e-6 deg at a
  // 500 px focal length. That, not the solver, bounds what "exact" can mean here.
  EXPECT_LT(worst_edge, 1e-5);

  for (const std::string input :
       {"--relative_poses '" + (dir / "edges.txt") + "'", "--database_path '" + db + "'"}) {
    const test::CommandResult averaged =
        test::RunCommand(test::RamapCommand() + "rotation_averager " + input + " --output_path '" +
                         (dir / "rot.txt") + "'");
    ASSERT_EQ(averaged.exit_code, 0) << averaged.output;
    EXPECT_NE(averaged.output.find("certified globally optimal"), std::string::npos)
        << averaged.output;
    const auto rotations = ReadRotationFile(dir / "rot.txt");
    ASSERT_EQ(rotations.size(), truth.size());
    EXPECT_LT(MaxAlignedErrorDeg(rotations, truth), 1e-5) << input;
  }
}

TEST(RotationCommands, UnusableInputFailsWithAMessageAndWritesNothing) {
  test::TempDir dir;
  MakeScene(dir);
  const std::string db = dir / "scene/database.db";
  // The same database without verified geometries.
  std::filesystem::copy_file(db, dir / "empty.db");
  ASSERT_EQ(
      test::RunCommand("sqlite3 '" + (dir / "empty.db") + "' 'DELETE FROM two_view_geometries;'")
          .exit_code,
      0);
  for (const std::string command :
       {std::string("relative_poses"), std::string("rotation_averager")}) {
    const test::CommandResult result =
        test::RunCommand(test::RamapCommand() + command + " --database_path '" +
                         (dir / "empty.db") + "' --output_path '" + (dir / "out.txt") + "'");
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_NE(result.output.find(dir / "empty.db"), std::string::npos) << result.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
  }
  const test::CommandResult none = test::RunCommand(
      test::RamapCommand() + "rotation_averager --output_path '" + (dir / "out.txt") + "'");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("--database_path or --relative_poses"), std::string::npos);
  const test::CommandResult both =
      test::RunCommand(test::RamapCommand() + "rotation_averager --database_path '" + db +
                       "' --relative_poses x --output_path '" + (dir / "out.txt") + "'");
  EXPECT_NE(both.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
}

}  // namespace
}  // namespace ramap
