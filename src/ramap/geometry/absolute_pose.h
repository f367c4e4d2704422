// A camera's pose from its bearings to known 3D points: Kneip's P3P (Kneip, Scaramuzza, Siegwart,
// "A novel parametrization of the perspective-three-point problem", CVPR 2011) inside RANSAC, then
// a nonlinear refinement on the inliers, both OpenGV's. Bearings rather than pixels, so any
// camera model (fisheye included) is handled alike.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "ramap/scene/rigid3.h"

namespace ramap {

struct AbsolutePoseOptions {
  // Largest angle between a bearing and the direction to its point for an inlier (the caller
  // converts its pixel bound with the focal length).
  double max_angular_error_rad = 4.0 / 1000.0;
  int max_iterations = 1000;
  double probability = 0.999;
  // Fewer inliers give no pose.
  int min_num_inliers = 30;
};

struct AbsolutePose {
  Rigid3d cam_from_world;
  std::vector<int> inliers;  // indices into the input
};

// The pose whose camera sees `points_world[k]` along `bearings[k]` (unit, camera frame) for the
// most k; none when fewer than min_num_inliers agree.
std::optional<AbsolutePose> EstimateAbsolutePose(const std::vector<Eigen::Vector3d>& bearings,
                                                 const std::vector<Eigen::Vector3d>& points_world,
                                                 const AbsolutePoseOptions& options);

// The indices k whose bearing is within `max_angular_error_rad` of the direction to
// points_world[k] seen from `cam_from_world`.
std::vector<int> AbsolutePoseInliers(const Rigid3d& cam_from_world,
                                     const std::vector<Eigen::Vector3d>& bearings,
                                     const std::vector<Eigen::Vector3d>& points_world,
                                     double max_angular_error_rad);

}  // namespace ramap
