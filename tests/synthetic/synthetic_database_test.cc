// The synthetic scene through the COLMAP database writer and reader: what `ramap synthesize`
// writes must read back unchanged, and COLMAP must reconstruct it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <map>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(SyntheticDatabase, RoundTripsThroughTheColmapDatabase) {
  SyntheticSceneOptions options;
  options.num_images = 15;
  options.num_points = 600;
  options.num_outlier_pairs = 2;
  options.keypoint_columns = 6;  // as COLMAP stores SIFT: the extra columns survive the trip
  const SyntheticScene scene = BuildSyntheticScene(options);
  test::TempDir dir;
  WriteColmapDatabase(scene.database, dir / "database.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "database.db");

  ASSERT_EQ(read.cameras.size(), 1u);
  EXPECT_EQ(read.cameras.at(1).params, scene.database.cameras.at(1).params);
  ASSERT_EQ(read.images.size(), scene.database.images.size());
  for (const auto& [image_id, image] : scene.database.images) {
    EXPECT_EQ(read.images.at(image_id).name, image.name);
    EXPECT_EQ(read.keypoints.at(image_id).num_cols, 6);
    EXPECT_EQ(read.keypoints.at(image_id).data, scene.database.keypoints.at(image_id).data);
  }
  ASSERT_EQ(read.matches.size(), scene.database.matches.size());
  for (const auto& [pair_id, matches] : scene.database.matches) {
    ASSERT_EQ(read.matches.at(pair_id).size(), matches.size());
  }
  ASSERT_EQ(read.two_view_geometries.size(), scene.database.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    const TwoViewGeometry& other = read.two_view_geometries.at(pair_id);
    EXPECT_EQ(other.config, geometry.config);
    EXPECT_EQ(other.inlier_matches.size(), geometry.inlier_matches.size());
    EXPECT_TRUE(other.E.isApprox(geometry.E, 1e-12));
    EXPECT_LT(other.cam2_from_cam1.rotation.angularDistance(geometry.cam2_from_cam1.rotation),
              1e-12);
  }
}

// An independent check of the synthetic data's conventions (pixel frame, pair order, E, inlier
// indices): COLMAP's own incremental mapper must recover the true relative rotations.
TEST(SyntheticDatabase, ColmapMapperRecoversTheTrueRotations) {
  RAMAP_REQUIRE_COLMAP();
  SyntheticSceneOptions options;
  // An orbit: wide baselines, so that COLMAP's initial pair (16 degrees of triangulation angle)
  // is found; forward motion rarely offers one.
  options.path = SyntheticPath::kCircle;
  options.num_images = 16;
  options.num_points = 1500;
  // Without noise COLMAP must agree to the precision of float32 keypoints (measured: 8e-6 deg;
  // with 0.5 px noise and 10% outliers, 0.17 deg).
  options.pixel_noise_sigma = 0.0;
  options.outlier_ratio = 0.0;
  const SyntheticScene scene = BuildSyntheticScene(options);
  test::TempDir dir;
  WriteColmapDatabase(scene.database, dir / "database.db");
  const test::CommandResult mapper =
      test::RunCommand("mkdir -p " + (dir / "images") + " " + (dir / "sparse") +
                       " && colmap mapper --database_path " + (dir / "database.db") +
                       " --image_path " + (dir / "images") + " --output_path " + (dir / "sparse") +
                       " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
                       " --Mapper.ba_refine_extra_params 0 --Mapper.num_threads 2");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  std::map<std::string, Eigen::Quaterniond> poses;
  for (const auto& [image_id, image] : ReadColmapModel(dir / "sparse/0").images) {
    poses[image.name] = image.cam_from_world.rotation;
  }
  ASSERT_EQ(poses.size(), static_cast<size_t>(options.num_images));
  double worst_deg = 0.0;
  for (const auto& [id1, image1] : scene.ground_truth.images) {
    for (const auto& [id2, image2] : scene.ground_truth.images) {
      if (id1 >= id2) continue;
      const Eigen::Quaterniond truth =
          image2.cam_from_world.rotation * image1.cam_from_world.rotation.conjugate();
      const Eigen::Quaterniond colmap = poses.at(image2.name) * poses.at(image1.name).conjugate();
      worst_deg = std::max(worst_deg, truth.angularDistance(colmap) * 180.0 / M_PI);
    }
  }
  std::cout << "colmap mapper on a synthetic scene: worst relative rotation error " << worst_deg
            << " deg\n";
  EXPECT_LT(worst_deg, 1e-3);
}

}  // namespace
}  // namespace ramap
