// Pose priors from a 4.x database's pose_priors table, in its Cartesian coordinate system and
// with its covariance: `ramap mapper` aligns the model in that frame without being told the
// priors' type.
#include <gtest/gtest.h>

#include "ramap/io/colmap_database.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(PosePriorDatabase, CartesianPriorsOfA4xDatabaseAlign) {
  test::TempDir dir;
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kCircle;
  options.num_images = 12;
  options.num_points = 800;
  const SyntheticScene scene = BuildSyntheticScene(options);
  FeatureDatabase database = scene.database;
  // Metres in a local frame, far from any latitude and longitude (as WGS84 they would be refused).
  for (auto& [image_id, image] : database.images) {
    const Eigen::Vector3d center =
        CameraCenter(scene.ground_truth.images.at(image_id).cam_from_world);
    image.prior_translation = center + Eigen::Vector3d(5000, -3000, 250);
    image.prior_coordinate_system = PriorCoordinateSystem::kCartesian;
    image.prior_position_covariance = Eigen::Matrix3d::Identity() * 0.25;
  }
  WriteColmapDatabase(database, dir / "db.db", DatabaseGeneration::kColmap4);

  const test::CommandResult result =
      test::RunCommand("'" + test::RamapBinary() + "' mapper --database_path '" + (dir / "db.db") +
                       "' --output_path '" + (dir / "sparse") + "' 2>&1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("pose priors: 12 of 12 usable (database, xyz)"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("model 0 aligned to its priors: 12 of 12"), std::string::npos)
      << result.output;
  // The inlier bound is 3 x the priors' 3D standard deviation: sqrt(3 x 0.25) m from the
  // database's covariance (the default deviations, 3, 3, 6 m, would give 22 m).
  EXPECT_NE(result.output.find("priors within 2.60 m"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace ramap
