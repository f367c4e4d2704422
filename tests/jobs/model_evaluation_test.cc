// EvaluateModel as `ramap evaluate` runs it: the input images taken from a list, a database or the
// model and ground truth together; a model equal to the truth up to a similarity scores exactly;
// ground truth of another scene, or matched by index without the input named, is refused.
#include "ramap/jobs/model_evaluation.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iomanip>

#include "ramap/geometry/alignment.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// A noise-free 10-frame line: its truth written as a COLMAP model (ground truth with names) at
// gt/, and an estimate at est/: the truth moved by a similarity, frames 9 and 10 unregistered.
struct Written {
  SyntheticScene scene;
  ModelEvaluationInput input;
};

Written Write(const test::TempDir& dir) {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 10);
  options.num_points = 300;
  Written written{BuildSyntheticScene(options), {}};
  WriteColmapModel(written.scene.ground_truth, dir / "gt", ModelFormat::kBinary);
  Reconstruction estimate = written.scene.ground_truth;
  estimate.points3D.clear();
  for (auto& [id, image] : estimate.images) {
    for (Point2D& point : image.points2D) point.point3D_id = kInvalidPoint3DId;
  }
  estimate.images.erase(9);
  estimate.images.erase(10);
  const Sim3d moved(0.25, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitY())),
                    Eigen::Vector3d(5, -3, 2));
  for (auto& [id, image] : estimate.images) {
    image.cam_from_world = TransformPose(moved, image.cam_from_world);
  }
  WriteColmapModel(estimate, dir / "est", ModelFormat::kBinary);
  written.input.model_path = dir / "est";
  written.input.ground_truth_path = dir / "gt";
  written.input.ground_truth_format = GroundTruthFormat::kColmap;
  return written;
}

TEST(ModelEvaluation, WithoutAListTheInputIsTheModelsAndTheTruthsImages) {
  test::TempDir dir;
  const Written written = Write(dir);
  const PoseEvaluation evaluation = EvaluateModel(written.input, PoseEvaluationOptions());
  EXPECT_EQ(evaluation.num_images, 10);  // the truth's images, registered or not
  EXPECT_EQ(evaluation.num_registered, 8);
  EXPECT_EQ(evaluation.num_with_ground_truth, 10);
  // The estimate is the truth moved by a similarity: float64 model files, errors of rounding only.
  EXPECT_LT(evaluation.rotation_error_max_deg, 1e-6);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-9);
}

TEST(ModelEvaluation, AnImageListOrADatabaseNamesTheInput) {
  test::TempDir dir;
  Written written = Write(dir);
  std::ofstream(dir / "list.txt") << "frame_000001.png\nframe_000002.png\nframe_000010.png\n";
  ModelEvaluationInput listed = written.input;
  listed.image_list_path = dir / "list.txt";
  const PoseEvaluation from_list = EvaluateModel(listed, PoseEvaluationOptions());
  EXPECT_EQ(from_list.num_images, 3);
  EXPECT_EQ(from_list.num_registered, 2);
  EXPECT_EQ(from_list.num_estimated_not_in_input, 6);

  // The database holds frames 1-10 and one more image with no pose anywhere.
  FeatureDatabase database = written.scene.database;
  database.images[11] = database.images.at(10);
  database.images[11].image_id = 11;
  database.images[11].name = "extra.png";
  database.keypoints[11] = database.keypoints.at(10);
  WriteColmapDatabase(database, dir / "database.db");
  ModelEvaluationInput from_database = written.input;
  from_database.database_path = dir / "database.db";
  const PoseEvaluation evaluation = EvaluateModel(from_database, PoseEvaluationOptions());
  EXPECT_EQ(evaluation.num_images, 11);
  EXPECT_EQ(evaluation.num_registered, 8);
  EXPECT_EQ(evaluation.num_with_ground_truth, 10);
}

TEST(ModelEvaluation, GroundTruthOfAnotherSceneIsRefused) {
  test::TempDir dir;
  const Written written = Write(dir);
  Reconstruction other = written.scene.ground_truth;
  for (auto& [id, image] : other.images) image.name = "other_" + image.name;
  WriteColmapModel(other, dir / "other", ModelFormat::kBinary);
  ModelEvaluationInput input = written.input;
  input.ground_truth_path = dir / "other";
  test::ExpectInputError([&] { EvaluateModel(input, PoseEvaluationOptions()); },
                         {dir / "other", "none of the 8 images of the model", "ground-truth pose"});
  std::ofstream(dir / "list.txt") << "nowhere.png\n";
  input.image_list_path = dir / "list.txt";
  // A list naming no image of the model nor of the ground truth is said as such, naming the list.
  test::ExpectInputError(
      [&] { EvaluateModel(input, PoseEvaluationOptions()); },
      {"--image_list", "none of the 1 images of", "list.txt (nowhere.png)", "is in the model"});
}

TEST(ModelEvaluation, GroundTruthByIndexNeedsTheInputNamedUnlessEveryImageIsRegistered) {
  test::TempDir dir;
  const Written written = Write(dir);
  // KITTI: world_from_cam of the ten frames, one 3x4 matrix a line, matched by index.
  {
    std::ofstream kitti(dir / "poses.txt");
    kitti << std::setprecision(17);
    for (const auto& [id, image] : written.scene.ground_truth.images) {
      const Rigid3d world_from_cam = image.cam_from_world.Inverse();
      const Eigen::Matrix<double, 3, 4> m = world_from_cam.ToMatrix();
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) kitti << m(r, c) << (r == 2 && c == 3 ? "\n" : " ");
      }
    }
  }
  ModelEvaluationInput input = written.input;
  input.ground_truth_path = dir / "poses.txt";
  input.ground_truth_format = GroundTruthFormat::kKitti;
  test::ExpectInputError([&] { EvaluateModel(input, PoseEvaluationOptions()); },
                         {"poses.txt", "8 images for 10 poses", "--image_list or --database_path"});
  std::ofstream list(dir / "list.txt");
  for (const auto& [id, image] : written.scene.ground_truth.images) list << image.name << "\n";
  list.close();
  input.image_list_path = dir / "list.txt";
  const PoseEvaluation evaluation = EvaluateModel(input, PoseEvaluationOptions());
  EXPECT_EQ(evaluation.num_registered, 8);
  EXPECT_EQ(evaluation.num_with_ground_truth, 10);
  // 17 digits of each matrix entry read back within rounding.
  EXPECT_LT(evaluation.rotation_error_max_deg, 1e-6);
}

}  // namespace
}  // namespace ramap
