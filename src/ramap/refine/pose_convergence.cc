#include "ramap/refine/pose_convergence.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace ramap {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

// Successive accepted steps below the tolerance before the solve ends: one small step can follow a
// shrunken trust region without the poses having settled.
constexpr int kNumStillSteps = 2;

// Ceres's trust-region strategies grow the region after a step whose cost fell by more than this
// fraction of what their model predicted (dogleg: to three times the step, if that is larger).
constexpr double kWellPredicted = 0.75;

Eigen::Quaterniond Rotation(const PoseBlock& pose) {
  return Eigen::Quaterniond(pose[3], pose[0], pose[1], pose[2]).normalized();
}

Eigen::Vector3d Centre(const PoseBlock& pose) {
  return -(Rotation(pose).conjugate() * pose.tail<3>());
}

}  // namespace

PoseConvergence::PoseConvergence(const std::map<uint32_t, PoseBlock>* poses,
                                 std::map<uint32_t, double> median_depths,
                                 std::vector<RefinedIntrinsics> intrinsics, double tolerance_deg,
                                 double min_trust_region_radius)
    : poses_(poses),
      median_depths_(std::move(median_depths)),
      intrinsics_(std::move(intrinsics)),
      tolerance_deg_(tolerance_deg),
      min_trust_region_radius_(min_trust_region_radius) {
  Remember();
}

ceres::CallbackReturnType PoseConvergence::operator()(const ceres::IterationSummary& summary) {
  // The radius Ceres reports is the one after this iteration's update.
  const double radius_before =
      std::exchange(last_trust_region_radius_, summary.trust_region_radius);
  // A rejected step leaves the state where it was: it says nothing about convergence.
  if (summary.iteration == 0 || !summary.step_is_successful) return ceres::SOLVER_CONTINUE;
  // A step is small either because the solution is near or because rejected steps shrank the
  // trust region: only the first counts. The region grows again on steps its model predicts well,
  // as near a minimum, and stays small while the solve crawls along a curved valley (a focal length
  // far from the truth). A well-predicted step that did not grow it was not bounded by it.
  const bool unbounded =
      summary.relative_decrease > kWellPredicted && summary.trust_region_radius == radius_before;
  const bool trusted = summary.trust_region_radius >= min_trust_region_radius_ || unbounded;
  num_still_steps_ = trusted && LargestMotionDeg() < tolerance_deg_ ? num_still_steps_ + 1 : 0;
  Remember();
  if (num_still_steps_ < kNumStillSteps) return ceres::SOLVER_CONTINUE;
  stopped_ = true;
  return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
}

double PoseConvergence::LargestMotionDeg() const {
  if (poses_ == nullptr) return IntrinsicsMotionRad() * kDegPerRad;
  double largest_rad = 0.0;
  for (const auto& [image_id, pose] : *poses_) {
    const PoseBlock& last = last_poses_.at(image_id);
    largest_rad = std::max(largest_rad, Rotation(pose).angularDistance(Rotation(last)));
    const auto depth = median_depths_.find(image_id);
    if (depth != median_depths_.end() && depth->second > 0.0) {
      largest_rad = std::max(largest_rad, (Centre(pose) - Centre(last)).norm() / depth->second);
    }
  }
  return std::max(largest_rad, IntrinsicsMotionRad()) * kDegPerRad;
}

double PoseConvergence::IntrinsicsMotionRad() const {
  double largest_rad = 0.0;
  for (size_t k = 0; k < intrinsics_.size(); ++k) {
    const RefinedIntrinsics& camera = intrinsics_[k];
    const double focal = camera.params[0];
    // Relative focal change and principal-point shift over the focal length: both angles.
    for (int i = 0; i < camera.num_focal_lengths + 2; ++i) {
      largest_rad =
          std::max(largest_rad, std::abs(camera.params[i] - last_intrinsics_[k][i]) / focal);
    }
  }
  return largest_rad;
}

void PoseConvergence::Remember() {
  if (poses_ != nullptr) last_poses_ = *poses_;
  last_intrinsics_.clear();
  for (const RefinedIntrinsics& camera : intrinsics_) {
    last_intrinsics_.emplace_back(camera.params, camera.params + camera.num_focal_lengths + 2);
  }
}

}  // namespace ramap
