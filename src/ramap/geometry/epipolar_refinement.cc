#include "ramap/geometry/epipolar_refinement.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace ramap {
namespace {

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

// Two unit vectors spanning the plane orthogonal to the unit vector t.
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& t) {
  const Eigen::Vector3d helper =
      std::abs(t.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = t.cross(helper).normalized();
  basis.col(1) = t.cross(basis.col(0));
  return basis;
}

// The cost and its Gauss-Newton normal equations at (R, t). Parameters: a rotation increment d
// applied as R exp([d]x) and a direction increment e applied as normalize(t + B e). With
// n = R f1 x f2 and r = t . n: dr/dd = f1 x (R^T (f2 x t)) and dr/de = B^T n.
struct Linearization {
  Matrix5d normal = Matrix5d::Zero();
  Vector5d gradient = Vector5d::Zero();
  double cost = 0;
};

Linearization Linearize(const std::vector<Eigen::Vector3d>& f1,
                        const std::vector<Eigen::Vector3d>& f2, const std::vector<int>& indices,
                        const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                        const Eigen::Matrix<double, 3, 2>& basis) {
  Linearization lin;
  const Eigen::Matrix3d Rt = R.transpose();
  for (const int k : indices) {
    const Eigen::Vector3d n = (R * f1[k]).cross(f2[k]);
    const double r = t.dot(n);
    Vector5d J;
    J.head<3>() = f1[k].cross(Rt * f2[k].cross(t));
    J.tail<2>() = basis.transpose() * n;
    lin.normal.noalias() += J * J.transpose();
    lin.gradient += r * J;
    lin.cost += r * r;
  }
  return lin;
}

}  // namespace

bool RefineEpipolarPose(const std::vector<Eigen::Vector3d>& bearings1,
                        const std::vector<Eigen::Vector3d>& bearings2,
                        const std::vector<int>& indices, Eigen::Matrix3d* R, Eigen::Vector3d* t,
                        const EpipolarRefinementOptions& options) {
  Eigen::Matrix3d rotation = *R;
  Eigen::Vector3d direction = t->normalized();
  Eigen::Matrix<double, 3, 2> basis = TangentBasis(direction);
  Linearization current = Linearize(bearings1, bearings2, indices, rotation, direction, basis);
  // Levenberg-Marquardt with the damping scaled by the diagonal (as Ceres does), started small:
  // most pairs arrive close to their minimum from the hypothesis.
  double damping = 1e-4;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (!(current.cost > 0) || current.gradient.cwiseAbs().maxCoeff() == 0) break;
    Matrix5d damped = current.normal;
    damped.diagonal() += damping * current.normal.diagonal().cwiseMax(1e-6);
    const Vector5d step = damped.ldlt().solve(-current.gradient);
    if (!step.allFinite()) break;
    const Eigen::Vector3d rotation_step = step.head<3>();
    const double angle = rotation_step.norm();
    const Eigen::Matrix3d candidate_rotation =
        angle > 0 ? Eigen::Matrix3d(rotation * Eigen::AngleAxisd(angle, rotation_step / angle))
                  : rotation;
    const Eigen::Vector3d candidate_direction = (direction + basis * step.tail<2>()).normalized();
    const Eigen::Matrix<double, 3, 2> candidate_basis = TangentBasis(candidate_direction);
    Linearization candidate = Linearize(bearings1, bearings2, indices, candidate_rotation,
                                        candidate_direction, candidate_basis);
    if (!(candidate.cost < current.cost)) {
      damping *= 4.0;
      if (damping > 1e16) break;
      continue;
    }
    const double decrease = (current.cost - candidate.cost) / current.cost;
    rotation = candidate_rotation;
    direction = candidate_direction;
    basis = candidate_basis;
    current = candidate;
    damping = std::max(damping / 3.0, 1e-12);
    if (decrease < options.function_tolerance ||
        step.norm() < options.parameter_tolerance * (1.0 + options.parameter_tolerance)) {
      break;
    }
  }
  if (!rotation.allFinite() || !direction.allFinite()) return false;
  // Re-orthonormalise: many small rotation steps drift from SO(3) by rounding.
  *R = Eigen::Quaterniond(rotation).normalized().toRotationMatrix();
  *t = direction;
  return true;
}

}  // namespace ramap
