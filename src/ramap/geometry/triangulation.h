// Triangulation of a point seen by cameras whose poses are fixed.
//
// The linear solve minimises the sum of squared distances of the point from the observation rays
// measured perpendicular to each ray in that camera's frame (the "midpoint" least squares in
// camera coordinates, see Hartley & Zisserman, "Multiple View Geometry", ch. 12); observations
// whose angular residual exceeds the bound are dropped one at a time, worst first, and the point
// is solved again (a robust variant in the spirit of COLMAP's track-by-track filtering).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "ramap/scene/rigid3.h"

namespace ramap {

struct RayObservation {
  Rigid3d cam_from_world;
  Eigen::Vector3d bearing = Eigen::Vector3d::UnitZ();  // unit, camera frame
};

struct TriangulationOptions {
  // Largest angle between an observation's ray and the direction to the point (COLMAP filters at
  // 4 px; with a ~1000 px focal length that is ~0.23 deg; the caller converts pixels to radians).
  double max_angular_error_rad = 4.0 / 1000.0;
  // A point needs two rays meeting at least at this angle (COLMAP's default 1.5 deg).
  double min_triangulation_angle_deg = 1.5;
  // Minimum number of observations kept.
  int min_num_observations = 2;

  void Check() const;
};

struct TriangulatedPoint {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  // Indices (into the input) of the observations the point agrees with.
  std::vector<int> inliers;
  double mean_angular_error_rad = 0.0;
  double max_triangulation_angle_deg = 0.0;
};

// The point the observations agree on, or empty when fewer than min_num_observations agree, the
// rays meet at too small an angle, or the point lies behind a camera.
std::optional<TriangulatedPoint> TriangulatePoint(
    const std::vector<RayObservation>& observations,
    const TriangulationOptions& options = TriangulationOptions());

// Depths (l1, l2) of two rays meeting a known offset: l1 ray1 - l2 ray2 = offset in least squares
// (the 2 x 2 normal equations by Cramer's rule). Empty when the rays are parallel (the normal
// equations' determinant below 1e-14). With unit rays, both depths positive means the two rays
// meet in front of both cameras.
std::optional<Eigen::Vector2d> TwoRayDepths(const Eigen::Vector3d& ray1,
                                            const Eigen::Vector3d& ray2,
                                            const Eigen::Vector3d& offset);

}  // namespace ramap
