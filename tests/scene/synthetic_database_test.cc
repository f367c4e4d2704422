// The synthetic scene through the COLMAP database writer and reader: what `ramap synthesize`
// writes must read back unchanged.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "ramap/io/colmap_database.h"
#include "ramap/scene/synthetic.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(SyntheticDatabase, RoundTripsThroughTheColmapDatabase) {
  SyntheticSceneOptions options;
  options.num_images = 15;
  options.num_points = 600;
  options.num_outlier_pairs = 2;
  const SyntheticScene scene = BuildSyntheticScene(options);
  test::TempDir dir;
  WriteColmapDatabase(scene.database, dir / "database.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "database.db");

  ASSERT_EQ(read.cameras.size(), 1u);
  EXPECT_EQ(read.cameras.at(1).params, scene.database.cameras.at(1).params);
  ASSERT_EQ(read.images.size(), scene.database.images.size());
  for (const auto& [image_id, image] : scene.database.images) {
    EXPECT_EQ(read.images.at(image_id).name, image.name);
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

}  // namespace
}  // namespace ramap

namespace ramap {
namespace {

struct ColmapImagePose {
  Eigen::Quaterniond rotation;
  Eigen::Vector3d translation;
};

// Poses by image name from a COLMAP images.txt (every other line holds the pose).
std::map<std::string, ColmapImagePose> ReadImagesTxtPoses(const std::string& path) {
  std::map<std::string, ColmapImagePose> poses;
  std::ifstream file(path);
  std::string line;
  bool pose_line = true;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (pose_line) {
      std::istringstream in(line);
      uint32_t image_id, camera_id;
      double qw, qx, qy, qz, tx, ty, tz;
      std::string name;
      in >> image_id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> camera_id >> name;
      poses[name] = {Eigen::Quaterniond(qw, qx, qy, qz), Eigen::Vector3d(tx, ty, tz)};
    }
    pose_line = !pose_line;
  }
  return poses;
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
  const test::CommandResult mapper = test::RunCommand(
      "mkdir -p " + (dir / "images") + " " + (dir / "sparse") +
      " && colmap mapper --database_path " + (dir / "database.db") + " --image_path " +
      (dir / "images") + " --output_path " + (dir / "sparse") +
      " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
      " --Mapper.ba_refine_extra_params 0 --Mapper.num_threads 2 && colmap model_converter"
      " --input_path " +
      (dir / "sparse/0") + " --output_path " + (dir / "sparse/0") + " --output_type TXT");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  const std::map<std::string, ColmapImagePose> poses =
      ReadImagesTxtPoses(dir / "sparse/0/images.txt");
  ASSERT_EQ(poses.size(), static_cast<size_t>(options.num_images));
  double worst_deg = 0.0;
  for (const auto& [id1, image1] : scene.ground_truth.images) {
    for (const auto& [id2, image2] : scene.ground_truth.images) {
      if (id1 >= id2) continue;
      const Eigen::Quaterniond truth =
          image2.cam_from_world.rotation * image1.cam_from_world.rotation.conjugate();
      const Eigen::Quaterniond colmap =
          poses.at(image2.name).rotation * poses.at(image1.name).rotation.conjugate();
      worst_deg = std::max(worst_deg, truth.angularDistance(colmap) * 180.0 / M_PI);
    }
  }
  std::cout << "colmap mapper on a synthetic scene: worst relative rotation error " << worst_deg
            << " deg\n";
  EXPECT_LT(worst_deg, 1e-3);
}

}  // namespace
}  // namespace ramap
