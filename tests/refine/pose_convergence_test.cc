#include "ramap/refine/pose_convergence.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace ramap {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

PoseBlock Pose(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& centre) {
  PoseBlock pose;
  pose << rotation.coeffs(), -(rotation * centre);
  return pose;
}

// The trust region's initial radius in these tests.
constexpr double kRadius = 1e4;

// `quality`: the cost's decrease over the one the step's model predicted.
ceres::IterationSummary Step(int iteration, bool successful, double radius = 3 * kRadius,
                             double quality = 0.5) {
  ceres::IterationSummary summary;
  summary.iteration = iteration;
  summary.step_is_successful = successful;
  summary.trust_region_radius = radius;
  summary.relative_decrease = quality;
  return summary;
}

// Turns camera `image_id` about the y axis by `angle_deg` more.
void Turn(std::map<uint32_t, PoseBlock>* poses, uint32_t image_id, double angle_deg) {
  PoseBlock& pose = poses->at(image_id);
  const Eigen::Quaterniond q(pose[3], pose[0], pose[1], pose[2]);
  const Eigen::Vector3d centre = -(q.conjugate() * pose.tail<3>());
  pose = Pose(
      Eigen::Quaterniond(Eigen::AngleAxisd(angle_deg * kRadPerDeg, Eigen::Vector3d::UnitY())) * q,
      centre);
}

std::map<uint32_t, PoseBlock> TwoCameras() {
  return {{1, Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero())},
          {2, Pose(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 0, 0))}};
}

TEST(PoseConvergence, StopsAfterTwoStillStepsAndIgnoresRejectedOnes) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  PoseConvergence still(&poses, {{1, 10.0}, {2, 10.0}}, {}, 1e-3, kRadius);
  EXPECT_EQ(still(Step(0, true)), ceres::SOLVER_CONTINUE);
  Turn(&poses, 2, 0.01);  // moving: well above the tolerance
  EXPECT_EQ(still(Step(1, true)), ceres::SOLVER_CONTINUE);
  Turn(&poses, 2, 5e-4);  // the first still step
  EXPECT_EQ(still(Step(2, true)), ceres::SOLVER_CONTINUE);
  // A rejected step leaves the state as it was: neither a still step nor a moving one.
  EXPECT_EQ(still(Step(3, false)), ceres::SOLVER_CONTINUE);
  EXPECT_FALSE(still.stopped());
  Turn(&poses, 2, 5e-4);  // the second
  EXPECT_EQ(still(Step(4, true)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);
  EXPECT_TRUE(still.stopped());
}

// Rejected steps shrink the trust region, and with it the next steps, wherever the solve is: small
// steps count only once the region is back to its initial size.
TEST(PoseConvergence, StepsInAShrunkenTrustRegionDoNotCount) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  PoseConvergence still(&poses, {}, {}, 1e-3, kRadius);
  for (int iteration = 1; iteration <= 4; ++iteration) {
    Turn(&poses, 2, 5e-4);
    EXPECT_EQ(still(Step(iteration, true, kRadius / 8)), ceres::SOLVER_CONTINUE);
  }
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(5, true, kRadius)), ceres::SOLVER_CONTINUE);
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(6, true, 3 * kRadius)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);
}

// In a region shrunk below its initial size, a step counts when it lay well inside it: Ceres's
// dogleg leaves the region as it was after a well-predicted step only then (a step that reached
// the region's edge triples it). A step predicted less well may have been cut by the region.
TEST(PoseConvergence, WellPredictedStepsInsideAShrunkenRegionCount) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  PoseConvergence still(&poses, {}, {}, 1e-3, kRadius);
  EXPECT_EQ(still(Step(0, true, kRadius)), ceres::SOLVER_CONTINUE);
  EXPECT_EQ(still(Step(1, false, kRadius / 2)), ceres::SOLVER_CONTINUE);  // rejected: halved
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(2, true, kRadius / 2, 0.6)), ceres::SOLVER_CONTINUE);  // may be cut
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(3, true, kRadius / 2, 1.5)), ceres::SOLVER_CONTINUE);  // inside: one
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(4, true, 3 * kRadius / 4, 1.5)), ceres::SOLVER_CONTINUE);  // at the edge
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(5, true, 3 * kRadius / 4, 1.5)), ceres::SOLVER_CONTINUE);  // inside: one
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(6, true, 3 * kRadius / 4, 0.9)), ceres::SOLVER_TERMINATE_SUCCESSFULLY);
}

TEST(PoseConvergence, AMovingStepStartsTheCountAgain) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  PoseConvergence still(&poses, {}, {}, 1e-3, kRadius);
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(1, true)), ceres::SOLVER_CONTINUE);
  Turn(&poses, 1, 2e-3);  // the other camera still turns
  EXPECT_EQ(still(Step(2, true)), ceres::SOLVER_CONTINUE);
  Turn(&poses, 2, 5e-4);
  EXPECT_EQ(still(Step(3, true)), ceres::SOLVER_CONTINUE);
  EXPECT_FALSE(still.stopped());
}

// The same displacement of a camera's centre is a large motion seen from points 1 unit away and a
// negligible one from points 1000 units away.
TEST(PoseConvergence, ACentreMovesByItsDisplacementOverItsPointsDepth) {
  for (const double depth : {1.0, 1000.0}) {
    std::map<uint32_t, PoseBlock> poses = TwoCameras();
    PoseConvergence still(&poses, {{1, depth}, {2, depth}}, {}, 1e-3, kRadius);
    for (int iteration = 1; iteration <= 2; ++iteration) {
      poses.at(2).tail<3>() += Eigen::Vector3d(1e-4, 0, 0);  // 0.0057 deg at depth 1
      still(Step(iteration, true));
    }
    EXPECT_EQ(still.stopped(), depth > 1.0) << "depth " << depth;
  }
}

TEST(PoseConvergence, ARefinedFocalLengthStillMovingKeepsItGoing) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  std::vector<double> params = {1000.0, 320.0, 240.0, 0.0};  // SIMPLE_RADIAL
  PoseConvergence still(&poses, {}, {{params.data(), 1}}, 1e-3, kRadius);
  for (int iteration = 1; iteration <= 3; ++iteration) {
    params[0] += 1.0;  // 0.1%: 0.057 deg
    EXPECT_EQ(still(Step(iteration, true)), ceres::SOLVER_CONTINUE);
  }
  for (int iteration = 4; iteration <= 5; ++iteration) {
    params[0] += 1e-3;
    params[3] += 0.01;  // distortion is not watched: it moves with the focal length
    still(Step(iteration, true));
  }
  EXPECT_TRUE(still.stopped());
}

TEST(PoseConvergence, WithoutPosesSettledIntrinsicsEndTheSolveWhileCamerasStillTurn) {
  std::map<uint32_t, PoseBlock> poses = TwoCameras();
  std::vector<double> params = {1000.0, 320.0, 240.0, 0.0};
  PoseConvergence watching_poses(&poses, {}, {{params.data(), 1}}, 1e-3, kRadius);
  PoseConvergence intrinsics_only(nullptr, {}, {{params.data(), 1}}, 1e-3, kRadius);
  for (int iteration = 1; iteration <= 2; ++iteration) {
    Turn(&poses, 2, 0.01);
    params[1] += 1e-3;
    watching_poses(Step(iteration, true));
    intrinsics_only(Step(iteration, true));
  }
  EXPECT_FALSE(watching_poses.stopped());
  EXPECT_TRUE(intrinsics_only.stopped());
  // A principal point still moving (0.02 px: 0.0011 deg at this focal length) keeps it going.
  PoseConvergence moving_principal_point(nullptr, {}, {{params.data(), 1}}, 1e-3, kRadius);
  for (int iteration = 1; iteration <= 3; ++iteration) {
    params[2] += 0.02;
    moving_principal_point(Step(iteration, true));
  }
  EXPECT_FALSE(moving_principal_point.stopped());
}

}  // namespace
}  // namespace ramap
