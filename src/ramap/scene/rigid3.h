// A rigid transform y = R x + t, the pose type used everywhere in ramap.
//
// Convention (as COLMAP): an image's pose is `cam_from_world`, x_cam = R * x_world + t. The
// camera centre in world coordinates is -R^T t.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ramap {

struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Rigid3d() = default;
  Rigid3d(const Eigen::Quaterniond& r, const Eigen::Vector3d& t) : rotation(r), translation(t) {}

  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const { return rotation * x + translation; }
  Rigid3d Inverse() const {
    const Eigen::Quaterniond r_inv = rotation.conjugate();
    return Rigid3d(r_inv, -(r_inv * translation));
  }
  Eigen::Matrix<double, 3, 4> ToMatrix() const {
    Eigen::Matrix<double, 3, 4> m;
    m.leftCols<3>() = rotation.toRotationMatrix();
    m.col(3) = translation;
    return m;
  }
};

// (a * b) * x = a * (b * x).
inline Rigid3d operator*(const Rigid3d& a, const Rigid3d& b) {
  return Rigid3d((a.rotation * b.rotation).normalized(), a.rotation * b.translation + a.translation);
}

// Camera centre in world coordinates of a cam_from_world pose.
inline Eigen::Vector3d CameraCenter(const Rigid3d& cam_from_world) {
  return -(cam_from_world.rotation.conjugate() * cam_from_world.translation);
}

}  // namespace ramap
