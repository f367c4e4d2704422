// Non-linear refinement of a relative pose on its inlier bearings.
//
// The cost is Kneip & Lynen's ("Direct Optimization of Frame-to-Frame Rotation", ICCV 2013):
// sum_k (t . (R f1_k x f2_k))^2 over the rotation R and the unit translation t, x2 = R x1 + t.
// Minimising over t alone gives the smallest eigenvalue of sum_k n_k n_k^T, n_k = R f1_k x f2_k,
// so the joint minimum is the eigenvalue objective's minimum. Five degrees of freedom (three of
// rotation, two of a direction), one residual per match: a hand-written Levenberg-Marquardt on
// 5 x 5 normal equations, which does per pair what a general solver did with an allocation per
// residual and automatic differentiation (that was a large share of the mapper's time on a long
// drive; docs/benchmark-history.md, "Relative poses").
#pragma once

#include <Eigen/Core>
#include <vector>

namespace ramap {

struct EpipolarRefinementOptions {
  int max_iterations = 50;
  // Stop when the cost changes by less than this fraction in an accepted step, or when a step
  // moves the parameters by less than parameter_tolerance (radians, unit vector). Noise-free pairs
  // have a zero-cost minimum that Gauss-Newton approaches quadratically, so these tight values
  // still reach it; on real pairs the cost stops moving after a few steps.
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
};

// Refines (R, t) in place on the matches `indices`, t kept unit length. Returns false (R, t left
// as they were) when the result is not finite.
bool RefineEpipolarPose(const std::vector<Eigen::Vector3d>& bearings1,
                        const std::vector<Eigen::Vector3d>& bearings2,
                        const std::vector<int>& indices, Eigen::Matrix3d* R, Eigen::Vector3d* t,
                        const EpipolarRefinementOptions& options = EpipolarRefinementOptions());

}  // namespace ramap
