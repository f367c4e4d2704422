// BundleAdjustModel: a model refined on its own observations, through its cameras' distortion,
// every point adjusted whatever the point cap says, and models without observations or with
// unusable cameras named.
#include "ramap/refine/model_bundle_adjustment.h"

#include <gtest/gtest.h>

#include <random>

#include "ramap/geometry/camera_projection.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// The noise-free truth of a small collection seen through a distorted camera whose calibration is
// known (held by BA), its points moved by up to 0.02 units (about 1 px at these depths) and every
// image but the first (the gauge) turned by up to 0.05 degrees.
Reconstruction PerturbedModel() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kUnordered, SyntheticPath::kLine, 8);
  options.num_points = 400;
  options.camera.model = CameraModel::kOpenCV;
  options.camera.params = {520, 515, 318, 243, -0.12, 0.03, 0.001, -0.0005};
  options.camera.has_prior_focal_length = true;
  Reconstruction model = BuildSyntheticScene(options).ground_truth;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& [id, point] : model.points3D)
    point.xyz += 0.02 * Eigen::Vector3d(u(rng), u(rng), u(rng));
  for (auto& [id, image] : model.images) {
    if (id == model.images.begin()->first) continue;
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    image.cam_from_world.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * M_PI / 180 * u(rng), axis)) *
        image.cam_from_world.rotation;
  }
  return model;
}

// The largest distance between an observation and its point projected through the model.
double MaxReprojectionErrorPx(const Reconstruction& model) {
  double max_error = 0;
  for (const auto& [id, image] : model.images) {
    for (const Point2D& point2D : image.points2D) {
      if (point2D.point3D_id == kInvalidPoint3DId) continue;
      const Eigen::Vector2d projected =
          ProjectToPixel(model.cameras.at(image.camera_id),
                         image.cam_from_world * model.points3D.at(point2D.point3D_id).xyz);
      max_error = std::max(max_error, (projected - point2D.xy).norm());
    }
  }
  return max_error;
}

TEST(ModelBundleAdjustment, EveryPointFitsItsObservationsThroughTheDistortedCamera) {
  Reconstruction model = PerturbedModel();
  const size_t num_points = model.points3D.size();
  ASSERT_GT(MaxReprojectionErrorPx(model), 1.0);
  BundleAdjustmentOptions options;
  options.max_num_points = 10;   // a cap the model's adjustment ignores...
  options.min_track_length = 3;  // ...as it ignores the skipped two-view points
  options.function_tolerance = 1e-12;
  options.pose_tolerance_deg = 0;  // run to convergence: the truth fits exactly
  const BundleAdjustmentSummary summary = BundleAdjustModel(&model, options, "sparse/0");
  EXPECT_EQ(model.points3D.size(), num_points);
  EXPECT_EQ(summary.num_points, static_cast<int>(num_points));
  EXPECT_EQ(summary.num_filtered_observations, 0);
  // Exact observations of an exact model: the solution fits them to Ceres' convergence, far
  // below a thousandth of a pixel.
  EXPECT_LT(MaxReprojectionErrorPx(model), 1e-3);
  EXPECT_LT(summary.final_rmse_px, 1e-3);
  EXPECT_GT(summary.initial_rmse_px, 0.1);
  // The given focal lengths and principal point are held; the distortion is refined
  // (refine_extra_params), and exact observations leave it at the truth up to Ceres' convergence.
  const std::vector<double>& params = model.cameras.at(1).params;
  EXPECT_EQ(std::vector<double>(params.begin(), params.begin() + 4),
            (std::vector<double>{520, 515, 318, 243}));
  const std::vector<double> distortion = {-0.12, 0.03, 0.001, -0.0005};
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(params[4 + k], distortion[k], 1e-5) << "k " << k;
}

TEST(ModelBundleAdjustment, AModelWithoutObservationsOrWithAnUnusableCameraIsNamed) {
  Reconstruction model = PerturbedModel();
  Reconstruction no_observations = model;
  for (auto& [id, image] : no_observations.images) {
    for (Point2D& point2D : image.points2D) point2D.point3D_id = kInvalidPoint3DId;
  }
  no_observations.points3D.clear();
  test::ExpectInputError(
      [&] { BundleAdjustModel(&no_observations, BundleAdjustmentOptions(), "sparse/0"); },
      {"sparse/0", "no observation"});
  model.cameras.at(1).params.resize(4);
  test::ExpectInputError([&] { BundleAdjustModel(&model, BundleAdjustmentOptions(), "sparse/0"); },
                         {"sparse/0", "camera 1", "parameters"});
}

}  // namespace
}  // namespace ramap
