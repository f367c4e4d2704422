// An image: its name, camera, pose and 2D observations, as in a COLMAP database / model.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ramap/scene/rigid3.h"

namespace ramap {

// COLMAP 3.8's invalid 3D point id (point3D_t is uint64).
constexpr uint64_t kInvalidPoint3DId = std::numeric_limits<uint64_t>::max();

// COLMAP's PosePrior::CoordinateSystem (databases of 3.10 on), with its integer values: what the
// three numbers of a pose prior are.
enum class PriorCoordinateSystem : int { kUndefined = -1, kWgs84 = 0, kCartesian = 1 };

struct Point2D {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // pixels, COLMAP convention (0.5 = pixel centre)
  uint64_t point3D_id = kInvalidPoint3DId;
};

struct Image {
  uint32_t image_id = 0;
  std::string name;
  uint32_t camera_id = 0;
  Rigid3d cam_from_world;
  // Observations, in the order of the image's keypoints.
  std::vector<Point2D> points2D;
  // Priors from the database: COLMAP 3.8's prior_q* / prior_t* columns, or the position of its
  // pose_priors table (3.10 on), which has no rotation (NULL or NaN there -> empty here).
  std::optional<Eigen::Quaterniond> prior_rotation;
  std::optional<Eigen::Vector3d> prior_translation;
  // What pose_priors says of the position (3.10 on): its coordinate system, its covariance (3.11
  // on) and the direction of gravity in the camera frame (4.x), where given.
  PriorCoordinateSystem prior_coordinate_system = PriorCoordinateSystem::kUndefined;
  std::optional<Eigen::Matrix3d> prior_position_covariance;
  std::optional<Eigen::Vector3d> prior_gravity;
};

}  // namespace ramap
