#include "ramap/geometry/alignment.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "ramap/util/error.h"

namespace ramap {
namespace {

Eigen::Matrix3Xd ToMatrix(const std::vector<Eigen::Vector3d>& points,
                          const std::vector<int>& indices) {
  Eigen::Matrix3Xd m(3, indices.size());
  for (size_t k = 0; k < indices.size(); ++k) m.col(k) = points[indices[k]];
  return m;
}

std::vector<Eigen::Vector3d> Select(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<int>& indices) {
  std::vector<Eigen::Vector3d> selected;
  selected.reserve(indices.size());
  for (int i : indices) selected.push_back(points[i]);
  return selected;
}

// Spread of both sets: the worse status wins (coincident is worse than collinear).
AlignmentStatus CheckBothSpread(const std::vector<Eigen::Vector3d>& source,
                                const std::vector<Eigen::Vector3d>& target, double ratio) {
  const AlignmentStatus s = CheckPointSpread(source, ratio);
  const AlignmentStatus t = CheckPointSpread(target, ratio);
  if (s == AlignmentStatus::kCoincidentPoints || t == AlignmentStatus::kCoincidentPoints) {
    return AlignmentStatus::kCoincidentPoints;
  }
  if (s != AlignmentStatus::kSuccess) return s;
  return t;
}

// Least squares over the selected correspondences; the caller has checked their spread.
Sim3d FitUmeyama(const std::vector<Eigen::Vector3d>& source,
                 const std::vector<Eigen::Vector3d>& target, const std::vector<int>& indices,
                 bool estimate_scale) {
  const Eigen::Matrix4d m =
      Eigen::umeyama(ToMatrix(source, indices), ToMatrix(target, indices), estimate_scale);
  const Eigen::Matrix3d scaled_rotation = m.topLeftCorner<3, 3>();
  // Umeyama returns a proper rotation (det +1) times the scale, so the cube root of the
  // determinant is the scale.
  const double scale = estimate_scale ? std::cbrt(scaled_rotation.determinant()) : 1.0;
  Sim3d sim;
  sim.scale = scale;
  sim.rotation = Eigen::Quaterniond(scaled_rotation / scale).normalized();
  sim.translation = m.topRightCorner<3, 1>();
  return sim;
}

std::vector<int> AllIndices(int n) {
  std::vector<int> indices(n);
  for (int i = 0; i < n; ++i) indices[i] = i;
  return indices;
}

double SquaredResidual(const Sim3d& sim, const Eigen::Vector3d& source,
                       const Eigen::Vector3d& target) {
  return (sim * source - target).squaredNorm();
}

// MSAC score (Torr & Zisserman 2000): truncated squared residuals, lower is better.
double MsacCost(const Sim3d& sim, const std::vector<Eigen::Vector3d>& source,
                const std::vector<Eigen::Vector3d>& target, double threshold_sq) {
  double cost = 0.0;
  for (size_t i = 0; i < source.size(); ++i) {
    cost += std::min(SquaredResidual(sim, source[i], target[i]), threshold_sq);
  }
  return cost;
}

std::vector<int> InlierIndices(const Sim3d& sim, const std::vector<Eigen::Vector3d>& source,
                               const std::vector<Eigen::Vector3d>& target, double threshold_sq) {
  std::vector<int> inliers;
  for (size_t i = 0; i < source.size(); ++i) {
    if (SquaredResidual(sim, source[i], target[i]) <= threshold_sq) {
      inliers.push_back(static_cast<int>(i));
    }
  }
  return inliers;
}

// Every triple when there are at most `max_samples` of them, else `max_samples` random ones.
std::vector<std::array<int, 3>> MinimalSamples(int n, int max_samples, uint64_t seed) {
  std::vector<std::array<int, 3>> samples;
  const double num_triples = static_cast<double>(n) * (n - 1) * (n - 2) / 6.0;
  if (num_triples <= max_samples) {
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        for (int c = b + 1; c < n; ++c) samples.push_back({a, b, c});
      }
    }
    return samples;
  }
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  while (static_cast<int>(samples.size()) < max_samples) {
    const int a = pick(rng);
    const int b = pick(rng);
    const int c = pick(rng);
    if (a == b || b == c || a == c) continue;
    samples.push_back({a, b, c});
  }
  return samples;
}

AlignmentResult AlignRobust(const std::vector<Eigen::Vector3d>& source,
                            const std::vector<Eigen::Vector3d>& target,
                            const AlignmentOptions& options) {
  const int n = static_cast<int>(source.size());
  const double threshold_sq = options.robust_max_error * options.robust_max_error;
  AlignmentResult result;
  result.status = AlignmentStatus::kNoConsensus;
  result.inliers.assign(n, false);

  double best_cost = std::numeric_limits<double>::infinity();
  Sim3d best;
  bool found = false;
  for (const std::array<int, 3>& sample :
       MinimalSamples(n, options.robust_max_iterations, options.random_seed)) {
    const std::vector<int> indices(sample.begin(), sample.end());
    if (CheckBothSpread(Select(source, indices), Select(target, indices),
                        options.min_spread_ratio) != AlignmentStatus::kSuccess) {
      continue;
    }
    const Sim3d sim = FitUmeyama(source, target, indices, options.estimate_scale);
    const double cost = MsacCost(sim, source, target, threshold_sq);
    if (cost < best_cost) {
      best_cost = cost;
      best = sim;
      found = true;
    }
  }
  if (!found) return result;

  // Refit on the inliers until they no longer change. A refit whose inliers are degenerate or
  // fewer than 3 keeps the previous fit.
  std::vector<int> used;
  Sim3d fit = best;
  std::vector<int> inliers = InlierIndices(fit, source, target, threshold_sq);
  for (int round = 0; round < options.robust_max_refits; ++round) {
    if (inliers.size() < 3 ||
        CheckBothSpread(Select(source, inliers), Select(target, inliers),
                        options.min_spread_ratio) != AlignmentStatus::kSuccess) {
      break;
    }
    fit = FitUmeyama(source, target, inliers, options.estimate_scale);
    used = inliers;
    inliers = InlierIndices(fit, source, target, threshold_sq);
    if (inliers == used) break;
  }
  if (used.empty()) return result;  // the best sample had fewer than 3 inliers
  result.status = AlignmentStatus::kSuccess;
  result.target_from_source = fit;
  for (int i : used) result.inliers[i] = true;
  result.num_inliers = static_cast<int>(used.size());
  return result;
}

}  // namespace

Sim3d Sim3d::Inverse() const {
  const Eigen::Quaterniond r_inv = rotation.conjugate();
  return Sim3d(1.0 / scale, r_inv, -(r_inv * translation) / scale);
}

Eigen::Matrix4d Sim3d::ToMatrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = scale * rotation.toRotationMatrix();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

Rigid3d TransformPose(const Sim3d& new_from_old, const Rigid3d& cam_from_old) {
  // x_cam_new = scale * x_cam_old = scale * (R_c R^T (x_new - t) / scale + t_c).
  const Eigen::Quaterniond rotation =
      (cam_from_old.rotation * new_from_old.rotation.conjugate()).normalized();
  return Rigid3d(rotation, new_from_old.scale * cam_from_old.translation -
                               rotation * new_from_old.translation);
}

const char* AlignmentStatusName(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kSuccess:
      return "success";
    case AlignmentStatus::kTooFewPoints:
      return "too_few_points";
    case AlignmentStatus::kCoincidentPoints:
      return "coincident_points";
    case AlignmentStatus::kCollinearPoints:
      return "collinear_points";
    case AlignmentStatus::kNoConsensus:
      return "no_consensus";
  }
  return "unknown";
}

void AlignmentOptions::Check() const {
  if (!(min_spread_ratio >= 0.0 && min_spread_ratio < 1.0)) {
    throw InputError("AlignmentOptions", "min_spread_ratio must be in [0, 1)");
  }
  if (robust && !(robust_max_error > 0.0)) {
    throw InputError("AlignmentOptions",
                     "robust alignment needs robust_max_error > 0 (in ground-truth units)");
  }
  if (robust_max_iterations < 1) {
    throw InputError("AlignmentOptions", "robust_max_iterations must be at least 1");
  }
  if (robust_max_refits < 1) {
    throw InputError("AlignmentOptions", "robust_max_refits must be at least 1");
  }
}

AlignmentStatus CheckPointSpread(const std::vector<Eigen::Vector3d>& points,
                                 double min_spread_ratio) {
  if (points.size() < 3) return AlignmentStatus::kTooFewPoints;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3Xd centred(3, points.size());
  for (size_t i = 0; i < points.size(); ++i) centred.col(i) = points[i] - centroid;
  const Eigen::Vector3d singular = Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues();
  if (!singular.allFinite()) return AlignmentStatus::kCoincidentPoints;
  // Relative to the points' magnitude, so rounding noise on far-away identical points counts as
  // coincident. The first singular value is the RMS spread times sqrt(n).
  const double rms_spread = singular(0) / std::sqrt(static_cast<double>(points.size()));
  if (rms_spread <= min_spread_ratio * (centroid.norm() + rms_spread) || rms_spread == 0.0) {
    return AlignmentStatus::kCoincidentPoints;
  }
  if (singular(1) <= min_spread_ratio * singular(0)) return AlignmentStatus::kCollinearPoints;
  return AlignmentStatus::kSuccess;
}

AlignmentResult AlignPoints(const std::vector<Eigen::Vector3d>& source,
                            const std::vector<Eigen::Vector3d>& target,
                            const AlignmentOptions& options) {
  options.Check();
  AlignmentResult result;
  if (source.size() != target.size() || source.size() < 3) {
    result.status = AlignmentStatus::kTooFewPoints;
    result.inliers.assign(source.size(), false);
    return result;
  }
  // A degenerate whole set is reported as such, also in robust mode (no triple could help).
  result.status = CheckBothSpread(source, target, options.min_spread_ratio);
  result.inliers.assign(source.size(), false);
  if (result.status != AlignmentStatus::kSuccess) return result;
  if (options.robust) return AlignRobust(source, target, options);
  const std::vector<int> all = AllIndices(static_cast<int>(source.size()));
  result.target_from_source = FitUmeyama(source, target, all, options.estimate_scale);
  result.inliers.assign(source.size(), true);
  result.num_inliers = static_cast<int>(source.size());
  return result;
}

}  // namespace ramap
