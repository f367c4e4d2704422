// What report.html draws of a model: cameras in capture order with their centres brought into the
// reference's frame about the page's origin, their fields of view and errors, an even subset of
// the points, reference cameras drawn like a model's, and the recall curve.
#include "ramap/report/report_scene.h"

#include <gtest/gtest.h>

#include "ramap/geometry/camera_projection.h"
#include "test_support.h"

namespace ramap {
namespace {

// Images named frame_10, frame_2, frame_1 (ids 1, 2, 3) at centres (10, 0, 0), (2, 0, 0),
// (1, 0, 0), looking along +z, through a 640 x 480 camera with fx 500, fy 400; `num_points`
// points at (k, 0, 20), each seen by images 1 and 2 at its exact projection.
Reconstruction Frames(int num_points) {
  Reconstruction model;
  model.cameras[1] = test::VgaPinholeCamera(500, 400);
  const std::vector<std::pair<std::string, double>> frames = {
      {"frame_10.png", 10}, {"frame_2.png", 2}, {"frame_1.png", 1}};
  for (uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = frames[id - 1].first;
    image.cam_from_world.translation = Eigen::Vector3d(-frames[id - 1].second, 0, 0);
    model.images[id] = image;
  }
  for (int k = 0; k < num_points; ++k) {
    Point3D& point = model.points3D[k + 1];
    point.xyz = Eigen::Vector3d(k, 0, 20);
    for (const uint32_t id : {1u, 2u}) {
      Image& image = model.images.at(id);
      const Eigen::Vector3d x = image.cam_from_world * point.xyz;
      image.points2D.push_back({ProjectToPixel(model.cameras.at(1), x), k + 1u});
      point.track.push_back({id, static_cast<uint32_t>(image.points2D.size() - 1)});
    }
  }
  return model;
}

TEST(ReportScene, SceneMiddleIsTheMeanCameraCentreInTheGivenFrame) {
  const Reconstruction model = Frames(0);
  EXPECT_TRUE(SceneMiddle(model).isApprox(Eigen::Vector3d(13.0 / 3, 0, 0)));
  const Sim3d moved(2.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 5, 0));
  EXPECT_TRUE(SceneMiddle(model, moved).isApprox(Eigen::Vector3d(26.0 / 3, 5, 0)));
  EXPECT_EQ(SceneMiddle(Reconstruction()), Eigen::Vector3d::Zero());
}

TEST(ReportScene, CamerasInCaptureOrderInTheReferenceFrameAboutTheOrigin) {
  const Reconstruction model = Frames(4);
  ReportSceneOptions options;
  options.origin = Eigen::Vector3d(1, 1, 1);
  const Sim3d reference_from_model(3.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 7));
  const nlohmann::json json =
      ReportModelJson("ramap", model, reference_from_model, nullptr, 10, options);
  EXPECT_EQ(json["name"], "ramap");
  EXPECT_EQ(json["num_registered"], 3);
  EXPECT_TRUE(json["sequence"]);
  const nlohmann::json& images = json["images"];
  EXPECT_EQ(images["name"], nlohmann::json({"frame_1.png", "frame_2.png", "frame_10.png"}));
  // Centre x 3 + (0, 0, 7) - origin: frame_1 at (3, 0, 7) - (1, 1, 1).
  EXPECT_EQ(images["center"], nlohmann::json({2, -1, 6, 5, -1, 6, 29, -1, 6}));
  // Half fields of view: 640 / (2 * 500) and 480 / (2 * 400), for each image.
  EXPECT_EQ(images["half_fov"][0], 0.64);
  EXPECT_EQ(images["half_fov"][1], 0.6);
  // Exact projections: each observing image's mean reprojection error is 0; frame_1 observes
  // nothing.
  EXPECT_TRUE(images["reprojection_error_px"][0].is_null());
  EXPECT_EQ(images["reprojection_error_px"][1], 0.0);
  EXPECT_EQ(images["reprojection_error_px"][2], 0.0);
  EXPECT_TRUE(images["rotation_error_deg"].is_null());
  // Points brought the same way: (k, 0, 20) -> (3k, 0, 67) - origin.
  EXPECT_EQ(json["points"]["total"], 4);
  EXPECT_EQ(json["points"]["count"], 4);
  EXPECT_EQ(json["points"]["xyz"][0], -1);
  EXPECT_EQ(json["points"]["xyz"][3], 2);
  EXPECT_EQ(json["points"]["xyz"][5], 66);
}

TEST(ReportScene, ThePointBudgetTakesAnEvenSubset) {
  const Reconstruction model = Frames(100);
  const nlohmann::json json = ReportModelJson("m", model, Sim3d(), nullptr, 10);
  EXPECT_EQ(json["points"]["total"], 100);
  ASSERT_EQ(json["points"]["count"], 10);
  // Every tenth point by id: x = 0, 10, 20, ...
  for (int k = 0; k < 10; ++k) EXPECT_EQ(json["points"]["xyz"][3 * k], 10 * k) << k;
  EXPECT_TRUE(json["points"]["rgb"].is_null());  // no point has a colour
}

TEST(ReportScene, AnEvaluationGivesEachScoredImageItsErrors) {
  const Reconstruction model = Frames(0);
  PoseEvaluation evaluation;
  ImageEvaluation scored;
  scored.name = "frame_2.png";
  scored.rotation_error_deg = 0.123456;
  scored.position_error = 0.5;
  ImageEvaluation unscored;
  unscored.name = "frame_10.png";  // rotation_error_deg -1: not evaluated
  evaluation.images = {scored, unscored};
  const nlohmann::json images = ReportModelJson("m", model, Sim3d(), &evaluation, 0)["images"];
  // Capture order: frame_1 (not in the evaluation), frame_2, frame_10.
  EXPECT_TRUE(images["rotation_error_deg"][0].is_null());
  EXPECT_EQ(images["rotation_error_deg"][1], 0.1235);  // four significant digits
  EXPECT_EQ(images["position_error"][1], 0.5);
  EXPECT_TRUE(images["rotation_error_deg"][2].is_null());
}

TEST(ReportScene, ReferenceCamerasAreDrawnWithTheModelsFieldOfView) {
  const Reconstruction like = Frames(0);
  const std::map<std::string, Rigid3d> poses = {
      {"b.png", Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -4))},
      {"a.png", Rigid3d()}};
  const nlohmann::json json = ReportReferenceJson("ground truth", poses, &like);
  EXPECT_EQ(json["name"], "ground truth");
  EXPECT_EQ(json["images"]["name"], nlohmann::json({"a.png", "b.png"}));
  EXPECT_EQ(json["images"]["center"], nlohmann::json({0, 0, 0, 0, 0, 4}));
  EXPECT_EQ(json["images"]["half_fov"][0], 0.64);
  EXPECT_TRUE(json["images"]["reprojection_error_px"].is_null());
  EXPECT_EQ(json["points"]["count"], 0);
}

TEST(ReportScene, RecallCurveAndAucInPercent) {
  PoseEvaluation evaluation;
  evaluation.recall_curve_thresholds_deg = {0, 1.5, 3};
  evaluation.recall_curve = {0, 0.25, 0.123456};
  evaluation.auc_thresholds_deg = {1, 3};
  evaluation.auc = {0.5, 0.75};
  const nlohmann::json json = ReportRecallCurveJson("ramap", evaluation);
  EXPECT_EQ(json["name"], "ramap");
  EXPECT_EQ(json["threshold_deg"], nlohmann::json({0, 1.5, 3}));
  EXPECT_EQ(json["recall"], nlohmann::json({0, 0.25, 0.1235}));
  EXPECT_EQ(json["auc"], nlohmann::json({{"1", 50}, {"3", 75}}));
}

}  // namespace
}  // namespace ramap
