#include "ramap/geometry/triangulation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ramap/geometry/rotation.h"
#include "ramap/util/option_check.h"

namespace ramap {
namespace {

std::optional<Eigen::Vector3d> SolveLinear(const std::vector<RayObservation>& observations,
                                           const std::vector<int>& used) {
  Eigen::Matrix3d lhs = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const int k : used) {
    const RayObservation& o = observations[k];
    const Eigen::Matrix3d R = o.cam_from_world.rotation.toRotationMatrix();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - o.bearing * o.bearing.transpose();
    lhs += R.transpose() * P * R;
    rhs -= R.transpose() * P * o.cam_from_world.translation;
  }
  Eigen::LDLT<Eigen::Matrix3d> ldlt(lhs);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const Eigen::Vector3d X = ldlt.solve(rhs);
  if (!X.allFinite()) return std::nullopt;
  return X;
}

double AngularError(const RayObservation& o, const Eigen::Vector3d& X) {
  const Eigen::Vector3d x = o.cam_from_world * X;
  return std::atan2(x.cross(o.bearing).norm(), x.dot(o.bearing));
}

}  // namespace

void TriangulationOptions::Check() const {
  CheckOption(max_angular_error_rad > 0, "TriangulationOptions::max_angular_error_rad", "> 0",
              max_angular_error_rad);
  CheckOption(min_triangulation_angle_deg >= 0, "TriangulationOptions::min_triangulation_angle_deg",
              ">= 0", min_triangulation_angle_deg);
  CheckOption(min_num_observations >= 2, "TriangulationOptions::min_num_observations", ">= 2",
              min_num_observations);
}

std::optional<TriangulatedPoint> TriangulatePoint(const std::vector<RayObservation>& observations,
                                                  const TriangulationOptions& options) {
  std::vector<int> used;
  for (int k = 0; k < static_cast<int>(observations.size()); ++k) {
    if (observations[k].bearing.allFinite() &&
        std::abs(observations[k].bearing.norm() - 1) < 1e-6) {
      used.push_back(k);
    }
  }
  while (static_cast<int>(used.size()) >= options.min_num_observations) {
    const std::optional<Eigen::Vector3d> X = SolveLinear(observations, used);
    if (!X) return std::nullopt;
    // Drop the worst observation while any disagrees.
    int worst = -1;
    double worst_error = options.max_angular_error_rad;
    double sum_error = 0.0;
    for (size_t u = 0; u < used.size(); ++u) {
      const double error = AngularError(observations[used[u]], *X);
      sum_error += error;
      if (error > worst_error) {
        worst_error = error;
        worst = static_cast<int>(u);
      }
    }
    if (worst >= 0) {
      used.erase(used.begin() + worst);
      continue;
    }
    TriangulatedPoint point;
    point.xyz = *X;
    point.inliers = used;
    point.mean_angular_error_rad = sum_error / used.size();
    // Widest angle between two rays from the camera centres to the point.
    double max_angle = 0.0;
    for (size_t a = 0; a < used.size(); ++a) {
      const Eigen::Vector3d ray_a =
          (*X - CameraCenter(observations[used[a]].cam_from_world)).normalized();
      for (size_t b = a + 1; b < used.size(); ++b) {
        const Eigen::Vector3d ray_b =
            (*X - CameraCenter(observations[used[b]].cam_from_world)).normalized();
        max_angle = std::max(max_angle, std::acos(std::clamp(ray_a.dot(ray_b), -1.0, 1.0)));
      }
    }
    point.max_triangulation_angle_deg = max_angle * kRadToDeg;
    if (point.max_triangulation_angle_deg < options.min_triangulation_angle_deg)
      return std::nullopt;
    return point;
  }
  return std::nullopt;
}

std::optional<Eigen::Vector2d> TwoRayDepths(const Eigen::Vector3d& ray1,
                                            const Eigen::Vector3d& ray2,
                                            const Eigen::Vector3d& offset) {
  const double p = ray1.squaredNorm(), q = ray2.squaredNorm(), c = ray1.dot(ray2);
  const double along1 = ray1.dot(offset), along2 = ray2.dot(offset);
  const double det = p * q - c * c;
  if (std::abs(det) < 1e-14) return std::nullopt;
  return Eigen::Vector2d((q * along1 - c * along2) / det, (c * along1 - p * along2) / det);
}

}  // namespace ramap
