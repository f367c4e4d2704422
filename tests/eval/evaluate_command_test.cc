// `ramap evaluate` end to end: on synthetic models written to disk, and on a real COLMAP model of
// fountain-P11 cross-checked against `colmap model_aligner`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "eval/eval_test_scenes.h"
#include "ramap/eval/pose_metrics.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "test_support.h"

namespace ramap::test {
namespace {

Reconstruction ModelOf(const std::map<std::string, Rigid3d>& poses) {
  return ModelOfPoses(poses, VgaPinholeCamera());
}

TEST(EvalEvaluateCommand, MatchesInProcessEvaluation) {
  std::mt19937_64 rng(30);
  const auto gt = RandomCameras(9, rng);
  auto est = Transformed(gt, RandomSim3(rng));
  // Some noise and one unregistered image, so that every number is non-trivial.
  est["img_03"] = RotatedInPlace(est.at("img_03"), Eigen::Vector3d(1, 2, 3), 4.0);
  est.erase("img_05");
  TempDir dir;
  WriteColmapModel(ModelOf(gt), dir / "gt", ModelFormat::kText);
  WriteColmapModel(ModelOf(est), dir / "est");

  const CommandResult run = RunCommand(
      RamapBinary() + " evaluate --model_path " + (dir / "est") + " --ground_truth " +
      (dir / "gt") + " --ground_truth_format colmap --output_path " + (dir / "report.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("8 / 9"), std::string::npos) << run.output;
  const nlohmann::json j = test::ReadJsonFile(dir / "report.json");

  // The model files hold the poses exactly (binary) or to 17 digits (text).
  const PoseEvaluation expected =
      EvaluatePoses(PosesByName(ReadColmapModel(dir / "est")),
                    PosesByName(ReadColmapModel(dir / "gt")), Names(gt));
  EXPECT_EQ(j["num_images"], 9);
  EXPECT_EQ(j["num_registered"], 8);
  EXPECT_NEAR(j["ate"]["rmse"].get<double>(), expected.ate_rmse, 1e-12);
  EXPECT_NEAR(j["rotation_error_deg"]["max"].get<double>(), 4.0, 1e-6);
  for (size_t k = 0; k < expected.auc.size(); ++k) {
    char key[8];
    std::snprintf(key, sizeof(key), "%g", expected.auc_thresholds_deg[k]);
    EXPECT_NEAR(j["relative"]["auc_by_threshold_deg"][key].get<double>(), expected.auc[k], 1e-12);
  }

  // An image list adds inputs the model and the ground truth do not know.
  {
    std::ofstream list(dir / "list.txt");
    for (const auto& [name, pose] : gt) list << name << "\n";
    list << "extra.jpg\n";
  }
  const CommandResult listed =
      RunCommand(RamapBinary() + " evaluate --model_path " + (dir / "est") + " --ground_truth " +
                 (dir / "gt") + " --ground_truth_format colmap --image_list " + (dir / "list.txt") +
                 " --output_path " + (dir / "listed.json"));
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  EXPECT_EQ(test::ReadJsonFile(dir / "listed.json")["num_images"], 10);

  const CommandResult bad =
      RunCommand(RamapBinary() + " evaluate --model_path " + (dir / "est") + " --ground_truth " +
                 (dir / "gt") + " --ground_truth_format nonsense");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("nonsense"), std::string::npos) << bad.output;
}

// The ground truth of another scene (no image name in common with the model) is an error naming
// both, not an evaluation of nothing (it printed "0 of 47 with ground truth" and exited 0).
TEST(EvalEvaluateCommand, GroundTruthOfAnotherSceneIsRefused) {
  std::mt19937_64 rng(31);
  const auto gt = RandomCameras(6, rng);
  std::map<std::string, Rigid3d> other;
  for (const auto& [name, pose] : gt) other["other_" + name] = pose;
  TempDir dir;
  WriteColmapModel(ModelOf(gt), dir / "gt", ModelFormat::kText);
  WriteColmapModel(ModelOf(other), dir / "est");
  const CommandResult run =
      RunCommand(RamapBinary() + " evaluate --model_path " + (dir / "est") + " --ground_truth " +
                 (dir / "gt") + " --ground_truth_format colmap --output_path " + (dir / "e.json"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("none of the 6 images of the model"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "e.json"));
}

// Ground truth without image names (TUM here) is matched by timestamp or index, so the input
// images must be known: from the model only when it registered every image.
TEST(EvalEvaluateCommand, IndexMatchedGroundTruthNeedsTheInputImages) {
  std::mt19937_64 rng(31);
  std::map<std::string, Rigid3d> gt;
  for (const auto& [name, pose] : RandomCameras(8, rng)) {
    gt["00000" + name.substr(name.size() - 1) + ".png"] = pose;
  }
  auto est = Transformed(gt, RandomSim3(rng));
  TempDir dir;
  WriteTumTrajectory(ModelOf(gt), dir / "gt.txt");
  WriteColmapModel(ModelOf(est), dir / "all");
  est.erase("000004.png");
  WriteColmapModel(ModelOf(est), dir / "partial");
  const std::string common = RamapBinary() + " evaluate --ground_truth " + (dir / "gt.txt") +
                             " --ground_truth_format tum --output_path " + (dir / "r.json") +
                             " --model_path ";

  CommandResult run = RunCommand(common + (dir / "all"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  nlohmann::json j = test::ReadJsonFile(dir / "r.json");
  EXPECT_EQ(j["num_evaluated"], 8);
  EXPECT_LT(j["ate"]["rmse"].get<double>(), 1e-9);

  run = RunCommand(common + (dir / "partial"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("--image_list"), std::string::npos) << run.output;

  {
    std::ofstream list(dir / "list.txt");
    for (const auto& [name, pose] : gt) list << name << "\n";
  }
  run = RunCommand(common + (dir / "partial") + " --image_list " + (dir / "list.txt"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  j = test::ReadJsonFile(dir / "r.json");
  EXPECT_EQ(j["num_images"], 8);
  EXPECT_EQ(j["num_registered"], 7);
  EXPECT_EQ(j["relative"]["num_failed_pairs"], 7);
  EXPECT_LT(j["ate"]["rmse"].get<double>(), 1e-9);  // the 7 are matched to their own poses
}

// `colmap model_aligner --robust_alignment 0` aligns a model to reference centres with Umeyama's
// similarity (COLMAP 3.8 Reconstruction::Align). Its aligned centres, read back from the model it
// writes, must sit at the distances from the ground truth that `ramap evaluate` reports.
TEST(EvalColmapCrossCheck, FountainAgreesWithColmapModelAligner) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/fountain-P11/images");
  RAMAP_REQUIRE_SHARED_DATA(gt_dir, "strecha/fountain-P11/gt_dense_cameras");
  ColmapRun run;
  run.image_dir = images;
  run.camera_params = "2759.48,2764.16,1520.69,1006.81";
  run.max_image_size = 640;
  const std::string model_path = CachedColmapModel(run);
  ASSERT_FALSE(model_path.empty());

  std::map<std::string, Rigid3d> gt;
  for (const GroundTruthPose& pose : ReadGroundTruth(gt_dir, GroundTruthFormat::kStrecha).poses) {
    gt[pose.image_name] = pose.cam_from_world;
  }
  ASSERT_EQ(gt.size(), 11u);
  TempDir dir;
  {
    std::ofstream ref(dir / "ref.txt");
    ref.precision(17);
    for (const auto& [name, pose] : gt) {
      const Eigen::Vector3d c = CameraCenter(pose);
      ref << name << " " << c.x() << " " << c.y() << " " << c.z() << "\n";
    }
  }
  std::filesystem::create_directories(dir / "aligned");
  const CommandResult aligner =
      RunCommand("colmap model_aligner --input_path '" + model_path + "' --output_path '" +
                 (dir / "aligned") + "' --ref_images_path '" + (dir / "ref.txt") +
                 "' --ref_is_gps 0 --robust_alignment 0 --estimate_scale 1 --min_common_images 3");
  ASSERT_EQ(aligner.exit_code, 0) << aligner.output;
  const Reconstruction aligned = ReadColmapModel(dir / "aligned");

  const CommandResult ours = RunCommand(
      RamapBinary() + " evaluate --model_path '" + model_path + "' --ground_truth '" + gt_dir +
      "' --ground_truth_format strecha --output_path '" + (dir / "report.json") + "'");
  ASSERT_EQ(ours.exit_code, 0) << ours.output;
  const nlohmann::json report = test::ReadJsonFile(dir / "report.json");
  ASSERT_EQ(report["alignment"]["status"], "success");
  EXPECT_EQ(report["num_images"], 11);

  int compared = 0;
  double colmap_sum = 0.0;
  double max_relative_difference = 0.0;
  for (const nlohmann::json& image : report["images"]) {
    const std::string name = image["name"];
    if (!image["registered"].get<bool>()) continue;
    const Image* colmap_image = nullptr;
    for (const auto& [id, candidate] : aligned.images) {
      if (candidate.name == name) colmap_image = &candidate;
    }
    ASSERT_NE(colmap_image, nullptr) << name;
    const double colmap_error =
        (CameraCenter(colmap_image->cam_from_world) - CameraCenter(gt.at(name))).norm();
    const double ramap_error = image["position_error"];
    EXPECT_NEAR(ramap_error, colmap_error, 1e-6 * colmap_error) << name;
    max_relative_difference =
        std::max(max_relative_difference, std::abs(ramap_error - colmap_error) / colmap_error);
    colmap_sum += colmap_error;
    ++compared;
  }
  EXPECT_EQ(compared, report["num_registered"].get<int>());
  EXPECT_GE(compared, 3);
  // COLMAP also prints its mean error (6 decimals).
  const size_t at = aligner.output.find("Alignment error: ");
  ASSERT_NE(at, std::string::npos) << aligner.output;
  EXPECT_NEAR(std::stod(aligner.output.substr(at + 17)), colmap_sum / compared, 1.5e-6);
  std::cout << "ramap vs colmap model_aligner: " << compared
            << " aligned centre errors agree to a relative " << max_relative_difference << "\n";

  std::cout << "COLMAP 3.8 on fountain-P11 (11 images, 640 px, fixed intrinsics):\n" << ours.output;
  RecordProperty("ate_rmse_m", std::to_string(report["ate"]["rmse"].get<double>()));
  RecordProperty("rotation_error_median_deg",
                 std::to_string(report["rotation_error_deg"]["median"].get<double>()));
}

}  // namespace
}  // namespace ramap::test
