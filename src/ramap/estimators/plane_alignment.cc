#include "ramap/estimators/plane_alignment.h"

#include <Eigen/Eigenvalues>

#include "ramap/util/error.h"

namespace ramap {

Sim3d PrincipalPlaneAlignment(const Reconstruction& model, const std::string& source) {
  if (model.points3D.size() < 3 || model.images.empty()) {
    throw InputError(source, "cannot find the principal plane of a model with " +
                                 std::to_string(model.points3D.size()) + " 3D points and " +
                                 std::to_string(model.images.size()) + " images");
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& [id, point] : model.points3D) centroid += point.xyz;
  centroid /= static_cast<double>(model.points3D.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& [id, point] : model.points3D) {
    const Eigen::Vector3d d = point.xyz - centroid;
    scatter += d * d.transpose();
  }
  // Eigenvalues in increasing order: the last two span the plane, the first is its normal.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  const Eigen::Vector3d x_axis = eigen.eigenvectors().col(2);
  const Eigen::Vector3d y_axis = eigen.eigenvectors().col(1);
  Eigen::Matrix3d new_from_old;
  new_from_old.row(0) = x_axis.transpose();
  new_from_old.row(1) = y_axis.transpose();
  new_from_old.row(2) = x_axis.cross(y_axis).transpose();
  // The cameras look at the scene from above: half a turn about x when the first is below.
  const Eigen::Vector3d first_center = CameraCenter(model.images.begin()->second.cam_from_world);
  if ((new_from_old * (first_center - centroid)).z() < 0) {
    new_from_old.row(1) *= -1;
    new_from_old.row(2) *= -1;
  }
  const Eigen::Quaterniond rotation(new_from_old);
  return Sim3d(1.0, rotation, -(new_from_old * centroid));
}

}  // namespace ramap
