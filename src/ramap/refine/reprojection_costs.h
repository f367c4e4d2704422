// The reprojection residuals of bundle adjustment, with their Jacobians written out for the pose
// and the point instead of automatic differentiation through the whole chain: BA's time went
// mostly into evaluating the residuals and their derivatives (dual numbers as wide as every
// parameter of a residual), and the chain rule through x = R(q) X + t is short. Only a camera
// model's projection is differentiated automatically, in the camera-frame point and the
// intrinsics alone.
//
// Parameter blocks, in this order: the pose (PoseBlock), the point, and (pixel residuals) the
// camera's parameters in COLMAP's order. One block per pose, not a rotation and a translation,
// halves the blocks of the reduced camera system that the Schur complement fills (and the locks
// its threads take around each).
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ramap/scene/camera.h"

namespace ramap {

// A camera's pose as one parameter block: the rotation as Eigen stores a quaternion (x, y, z, w;
// unit), then the translation; x_camera = R(q) X + t.
using PoseBlock = Eigen::Matrix<double, 7, 1>;

// d(q * X)/dq for Eigen's rotation of X by the unit quaternion q, with respect to q's
// coefficients (x, y, z, w).
Eigen::Matrix<double, 3, 4> RotatedPointJacobian(const Eigen::Quaterniond& q,
                                                 const Eigen::Vector3d& X);

// Pixel-scaled error on the normalised plane of an undistorted bearing: focal * (x/z - b/b_z).
// Blocks: pose (7), point (3).
ceres::CostFunction* NewNormalizedPlaneCost(const Eigen::Vector3d& bearing, double focal_px);

// Pixel error through the camera model: the projection of the point less the keypoint. Blocks:
// pose (7), point (3), the camera's parameters (NumCameraParams(model)).
// Null for a model without a perspective projection.
ceres::CostFunction* NewPixelCost(CameraModel model, const Eigen::Vector2d& keypoint);

}  // namespace ramap
