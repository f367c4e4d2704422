// `ramap compare`'s report.html: every succeeded run's model brought into the ground truth's frame
// by its evaluation's alignment, over the ground truth's cameras about their middle, with its
// recall curve, the runs' stage bars, the comparison and the last ramap run's summary.
#include "ramap/compare/comparison_page.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ramap/geometry/alignment.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// Runs on a noise-free 8-frame line: "COLMAP" and "ramap" wrote the truth in frames of their own
// (moved by similarities), "GLOMAP" failed; ramap's summary.json lies beside its model.
struct Runs {
  SyntheticScene scene;
  std::vector<std::string> names;
  std::map<std::string, Rigid3d> ground_truth;
  std::map<std::string, Reconstruction> models;
  Comparison comparison;
};

Reconstruction Moved(const Reconstruction& truth, const Sim3d& new_from_old) {
  Reconstruction moved = truth;
  for (auto& [id, image] : moved.images) {
    image.cam_from_world = TransformPose(new_from_old, image.cam_from_world);
  }
  for (auto& [id, point] : moved.points3D) point.xyz = new_from_old * point.xyz;
  return moved;
}

Runs MakeRuns(const test::TempDir& dir) {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 8);
  options.num_points = 200;
  Runs runs{BuildSyntheticScene(options), {}, {}, {}, {}};
  for (const auto& [id, image] : runs.scene.ground_truth.images) {
    runs.names.push_back(image.name);
    runs.ground_truth[image.name] = image.cam_from_world;
  }
  const std::vector<std::pair<std::string, Sim3d>> frames = {
      {"COLMAP", Sim3d(0.5, Eigen::Quaterniond(Eigen::AngleAxisd(1, Eigen::Vector3d::UnitX())),
                       Eigen::Vector3d(3, 0, 0))},
      {"GLOMAP", Sim3d()},
      {"ramap", Sim3d(2.0, Eigen::Quaterniond(Eigen::AngleAxisd(-2, Eigen::Vector3d::UnitZ())),
                      Eigen::Vector3d(0, -7, 1))}};
  for (const auto& [name, frame] : frames) {
    MapperRun run;
    run.name = name;
    run.seconds = 2.0;
    run.succeeded = name != "GLOMAP";
    if (run.succeeded) {
      runs.models[name] = Moved(runs.scene.ground_truth, frame);
      run.model_path = dir / (name + "/0");
      run.num_registered = 8;
      run.evaluation = EvaluatePoses(PosesByName(runs.models[name]), runs.ground_truth, runs.names);
    }
    runs.comparison.runs.push_back(run);
  }
  runs.comparison.runs[2].stage_seconds = {{"rotation averaging", 0.5}};
  fs::create_directories(dir / "ramap/0");
  std::ofstream(dir / "ramap/summary.json") << R"({"num_registered_images": 8})";
  runs.comparison.database_path = "scene/database.db";
  runs.comparison.num_images = 8;
  runs.comparison.reference = "ground truth gt (colmap)";
  return runs;
}

TEST(ComparisonPage, SucceededRunsInTheGroundTruthsFrameOverItsCameras) {
  test::TempDir dir;
  Runs runs = MakeRuns(dir);
  WriteComparisonPage(runs.comparison, runs.names, runs.ground_truth, "", "line", dir.path(),
                      &runs.models);
  const nlohmann::json page = test::ReportPageData(dir / "report.html");
  ASSERT_FALSE(page.is_null());
  EXPECT_EQ(page["kind"], "compare");
  EXPECT_EQ(page["title"], "line");
  EXPECT_EQ(page["subtitle"],
            "ramap compare: 3 mappers on scene/database.db (8 images); reference: ground truth gt "
            "(colmap)");
  EXPECT_EQ(page["position_unit"], "ground-truth units");
  // The failed run has no model and no curve.
  ASSERT_EQ(page["models"].size(), 2u);
  EXPECT_EQ(page["models"][0]["name"], "COLMAP");
  EXPECT_EQ(page["models"][1]["name"], "ramap");
  ASSERT_EQ(page["recall_curves"].size(), 2u);
  EXPECT_EQ(page["recall_curves"][1]["name"], "ramap");
  ASSERT_EQ(page["stage_seconds"].size(), 2u);
  EXPECT_EQ(page["stage_seconds"][1]["name"], "ramap");
  EXPECT_EQ(page["comparison"]["runs"].size(), 3u);
  EXPECT_EQ(page["summary"]["num_registered_images"], 8);
  EXPECT_EQ(page["summary_title"], "ramap's summary");

  // Both models, aligned, sit on the ground truth's cameras (7 significant digits of coordinates
  // about the middle, exact alignments of exact poses).
  const nlohmann::json& reference = page["reference"]["images"]["center"];
  ASSERT_EQ(reference.size(), 24u);
  for (const nlohmann::json& model : page["models"]) {
    const nlohmann::json& centers = model["images"]["center"];
    ASSERT_EQ(centers.size(), reference.size());
    for (size_t k = 0; k < centers.size(); ++k) {
      EXPECT_NEAR(centers[k].get<double>(), reference[k].get<double>(), 1e-5)
          << model["name"] << " coordinate " << k;
    }
  }
  // The origin is the middle of the ground truth's cameras: the reference's centres average 0.
  double sum = 0;
  for (size_t k = 0; k < reference.size(); k += 3) sum += reference[k].get<double>();
  EXPECT_NEAR(sum / 8, 0.0, 1e-6);
}

TEST(ComparisonPage, WithoutGroundTruthTheFirstModelIsTheReference) {
  test::TempDir dir;
  Runs runs = MakeRuns(dir);
  runs.comparison.runs[0].evaluation.reset();  // COLMAP is the reference: not evaluated
  WriteComparisonPage(runs.comparison, runs.names, {}, "", "line", dir.path(), &runs.models);
  const nlohmann::json page = test::ReportPageData(dir / "report.html");
  EXPECT_TRUE(page["reference"].is_null());
  EXPECT_EQ(page["position_unit"], "COLMAP model units");
  ASSERT_EQ(page["recall_curves"].size(), 1u);
  // About the middle of COLMAP's own cameras.
  double sum = 0;
  const nlohmann::json& centers = page["models"][0]["images"]["center"];
  for (size_t k = 0; k < centers.size(); k += 3) sum += centers[k].get<double>();
  EXPECT_NEAR(sum / 8, 0.0, 1e-6);
}

}  // namespace
}  // namespace ramap
