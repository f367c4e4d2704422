#include "ramap/geometry/absolute_pose.h"

#include <cmath>
#include <memory>
#include <opengv/absolute_pose/CentralAbsoluteAdapter.hpp>
#include <opengv/absolute_pose/methods.hpp>
#include <opengv/sac/Ransac.hpp>
#include <opengv/sac_problems/absolute_pose/AbsolutePoseSacProblem.hpp>

namespace ramap {
namespace {

// OpenGV's transformation [R | c] maps the camera frame to the world: R is world_from_cam's
// rotation and c the camera centre.
Rigid3d CamFromWorld(const opengv::transformation_t& world_from_cam) {
  const Eigen::Matrix3d R = world_from_cam.leftCols<3>();
  const Eigen::Quaterniond q(R.transpose());
  return Rigid3d(q.normalized(), -(R.transpose() * world_from_cam.col(3)));
}

}  // namespace

std::vector<int> AbsolutePoseInliers(const Rigid3d& cam_from_world,
                                     const std::vector<Eigen::Vector3d>& bearings,
                                     const std::vector<Eigen::Vector3d>& points_world,
                                     double max_angular_error_rad) {
  const double min_cos = std::cos(max_angular_error_rad);
  std::vector<int> inliers;
  for (size_t k = 0; k < bearings.size(); ++k) {
    const Eigen::Vector3d x = cam_from_world * points_world[k];
    const double norm = x.norm();
    if (norm > 0 && x.dot(bearings[k]) / (norm * bearings[k].norm()) >= min_cos)
      inliers.push_back(static_cast<int>(k));
  }
  return inliers;
}

std::optional<AbsolutePose> EstimateAbsolutePose(const std::vector<Eigen::Vector3d>& bearings,
                                                 const std::vector<Eigen::Vector3d>& points_world,
                                                 const AbsolutePoseOptions& options) {
  if (bearings.size() != points_world.size() ||
      static_cast<int>(bearings.size()) < std::max(options.min_num_inliers, 4)) {
    return std::nullopt;
  }
  opengv::bearingVectors_t f(bearings.begin(), bearings.end());
  for (Eigen::Vector3d& bearing : f) bearing.normalize();
  const opengv::points_t X(points_world.begin(), points_world.end());
  opengv::absolute_pose::CentralAbsoluteAdapter adapter(f, X);
  using Problem = opengv::sac_problems::absolute_pose::AbsolutePoseSacProblem;
  opengv::sac::Ransac<Problem> ransac;
  // A fixed seed (randomSeed false): the same input gives the same pose.
  ransac.sac_model_ = std::make_shared<Problem>(adapter, Problem::KNEIP, false);
  ransac.threshold_ = 1.0 - std::cos(options.max_angular_error_rad);
  ransac.max_iterations_ = options.max_iterations;
  ransac.probability_ = options.probability;
  if (!ransac.computeModel()) return std::nullopt;
  if (static_cast<int>(ransac.inliers_.size()) < options.min_num_inliers) return std::nullopt;

  adapter.sett(ransac.model_coefficients_.col(3));
  adapter.setR(ransac.model_coefficients_.leftCols<3>());
  const opengv::transformation_t refined =
      opengv::absolute_pose::optimize_nonlinear(adapter, ransac.inliers_);
  AbsolutePose pose;
  pose.cam_from_world = CamFromWorld(refined);
  pose.inliers = AbsolutePoseInliers(pose.cam_from_world, bearings, points_world,
                                     options.max_angular_error_rad);
  if (static_cast<int>(pose.inliers.size()) < options.min_num_inliers) return std::nullopt;
  return pose;
}

}  // namespace ramap
