// Stage 5 on one component: tracks triangulated through the averaged poses (moved into the priors'
// frame when aligned), the cameras written as given, and an image placed badly placed again.
#include "ramap/mapper/component_triangulation.h"

#include <gtest/gtest.h>

#include "ramap/estimators/bearings.h"
#include "ramap/graph/tracks.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// A pass's input for a noise-free 12-image collection, its tracks, and a component state holding
// its true rotations and centres as averaging would leave them.
class ComponentTriangulation : public ::testing::Test {
 protected:
  ComponentTriangulation()
      : scene_(BuildSyntheticScene(
            test::NoiseFree(SyntheticLayout::kUnordered, SyntheticPath::kLine, 12))),
        options_(test::AveragingOnly()),
        bearings_(ComputeBearings(scene_.database, "synthetic")) {}

  PassInput Input() const {
    return PassInput{scene_.database, options_, scene_.database.cameras, bearings_, pairs_, order_,
                     false,           priors_};
  }

  ComponentState AveragedState() const {
    ComponentState state;
    state.translations.emplace();
    state.translations->tracks = BuildTracks(scene_.database.two_view_geometries);
    for (const auto& [id, image] : scene_.ground_truth.images) {
      state.rotations[id] = image.cam_from_world.rotation;
      state.translations->positions.centers[id] = CameraCenter(image.cam_from_world);
    }
    return state;
  }

  SyntheticScene scene_;
  MapperOptions options_;
  ImageBearings bearings_;
  std::vector<ImagePair> pairs_;
  std::vector<uint32_t> order_;
  PosePriors priors_;
};

// Noise-free float32 keypoints: reprojection errors of ~1e-5 px.
constexpr double kExactPx = 1e-3;

TEST_F(ComponentTriangulation, AveragedPosesGiveTheTruePointsAndTheStageIsReported) {
  const ComponentState state = TriangulateAveragedPoses(Input(), AveragedState());
  ASSERT_EQ(state.poses.size(), 12u);
  for (const auto& [id, pose] : state.poses) {
    const Rigid3d& truth = scene_.ground_truth.images.at(id).cam_from_world;
    EXPECT_LT(pose.rotation.angularDistance(truth.rotation), 1e-12);
    EXPECT_LT((pose.translation - truth.translation).norm(), 1e-9);  // -R c, rounded
  }
  EXPECT_EQ(state.model.images.size(), 12u);
  EXPECT_GT(state.summary.num_points, 1000);
  EXPECT_EQ(static_cast<int>(state.model.points3D.size()), state.summary.num_points);
  EXPECT_GT(state.summary.num_observations, 2 * state.summary.num_points);
  EXPECT_LT(state.summary.mean_reprojection_error_px, kExactPx);
  ASSERT_EQ(state.report.timings.size(), 1u);
  EXPECT_EQ(state.report.timings[0].stage, stage::kTriangulation);
}

TEST_F(ComponentTriangulation, AlignedToPriorsThePosesMoveIntoThePriorsFrame) {
  ComponentState state = AveragedState();
  const Sim3d prior_from_model(2.5,
                               Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ())),
                               Eigen::Vector3d(100, -50, 7));
  state.prior_alignment.summary.aligned = true;
  state.prior_alignment.prior_from_model = prior_from_model;
  state = TriangulateAveragedPoses(Input(), std::move(state));
  for (const auto& [id, pose] : state.poses) {
    const Rigid3d expected =
        TransformPose(prior_from_model, scene_.ground_truth.images.at(id).cam_from_world);
    EXPECT_LT(pose.rotation.angularDistance(expected.rotation), 1e-12);
    EXPECT_LT((pose.translation - expected.translation).norm(), 1e-8);
  }
  // The points come out in the same frame: each true point moved by the similarity.
  int num_checked = 0;
  for (const auto& [id, point] : state.model.points3D) {
    const TrackElement& element = point.track.front();
    const uint64_t true_id =
        scene_.ground_truth.images.at(element.image_id).points2D[element.point2D_idx].point3D_id;
    ASSERT_NE(true_id, kInvalidPoint3DId);
    const Eigen::Vector3d expected =
        prior_from_model * scene_.ground_truth.points3D.at(true_id).xyz;
    // ~1e-5 px of keypoint rounding at depths of ~10 units and a scale of 2.5.
    EXPECT_LT((point.xyz - expected).norm(), 1e-4);
    ++num_checked;
  }
  EXPECT_GT(num_checked, 1000);
}

TEST_F(ComponentTriangulation, TheCamerasWrittenAreTheOnesGiven) {
  ComponentState state = AveragedState();
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [id, image] : scene_.ground_truth.images) poses[id] = image.cam_from_world;
  std::map<uint32_t, Camera> refined = scene_.database.cameras;
  refined.at(1).params[0] += 1.0;  // as bundle adjustment would have moved it
  const Reconstruction model =
      TriangulateComponent(Input(), poses, state.translations->tracks, bearings_, refined,
                           "after BA: ", options_.triangulation, &state);
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras.at(1).params, refined.at(1).params);
  EXPECT_EQ(static_cast<int>(model.points3D.size()), state.summary.num_points);
}

TEST_F(ComponentTriangulation, AnImageItsPointsLeaveOutIsPlacedAgain) {
  ComponentState state = TriangulateAveragedPoses(Input(), AveragedState());
  // Image 5 turned 30 degrees about its centre, as averaging may leave an image.
  const Rigid3d truth = scene_.ground_truth.images.at(5).cam_from_world;
  const Eigen::Quaterniond turned =
      Eigen::Quaterniond(Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitY())) *
      truth.rotation;
  state.poses[5] = Rigid3d(turned, -(turned * CameraCenter(truth)));
  state.model = TriangulateComponent(Input(), state.poses, state.translations->tracks, bearings_,
                                     scene_.database.cameras, "", options_.triangulation, &state);
  const int num_points_before = state.summary.num_points;

  state = ReregisterComponent(Input(), std::move(state));
  ASSERT_EQ(state.summary.reregistered_images.size(), 1u);
  EXPECT_EQ(state.summary.reregistered_images[0].image_id, 5u);
  EXPECT_TRUE(state.summary.reregistered_images[0].replaced);
  // Absolute pose from noise-free rays: the true pose up to the keypoints' rounding.
  EXPECT_LT(state.poses.at(5).rotation.angularDistance(truth.rotation) * 180 / M_PI, 1e-3);
  // Triangulated again: image 5's observations are back.
  EXPECT_GE(state.summary.num_points, num_points_before);
  EXPECT_GT(state.model.images.at(5).points2D.size(), 0u);
  int observed = 0;
  for (const Point2D& point : state.model.images.at(5).points2D) {
    observed += point.point3D_id != kInvalidPoint3DId;
  }
  EXPECT_GT(observed, 100);
}

TEST_F(ComponentTriangulation, ReregistrationOffLeavesTheStateAsItWas) {
  options_.reregistration.enable = false;
  ComponentState state = TriangulateAveragedPoses(Input(), AveragedState());
  // Image 5 placed badly, as above: still not tried.
  const Rigid3d truth = scene_.ground_truth.images.at(5).cam_from_world;
  state.poses[5] = Rigid3d(truth.rotation.conjugate(), truth.translation);
  const size_t num_points = state.model.points3D.size();
  state = ReregisterComponent(Input(), std::move(state));
  EXPECT_TRUE(state.summary.reregistered_images.empty());
  EXPECT_EQ(state.model.points3D.size(), num_points);
  EXPECT_EQ(state.poses.at(5).rotation.coeffs(), truth.rotation.conjugate().coeffs());
}

}  // namespace
}  // namespace ramap
