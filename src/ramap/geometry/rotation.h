// Angles: the one degree/radian conversion, and the angle between two directions or two
// rotations, in forms that stay accurate near zero.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace ramap {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kRadToDeg = 180.0 / M_PI;

// Angle between two vectors in radians, [0, pi]. atan2 of |a x b| and a . b stays accurate for
// nearly (anti)parallel vectors, where acos of the normalised dot product loses half its digits.
inline double AngleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Angle in radians of the rotation taking `a` to `b` (of a^-1 b), [0, pi]. 2 atan2(|v|, |w|) of
// the relative quaternion is accurate near 0, where 2 acos(|w|) is not.
inline double RotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = (a.conjugate() * b).normalized();
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

// The same in degrees.
inline double RotationAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return RotationAngle(a, b) * kRadToDeg;
}

}  // namespace ramap
