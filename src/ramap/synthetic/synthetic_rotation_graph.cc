#include "ramap/synthetic/synthetic_rotation_graph.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include "ramap/geometry/rotation.h"

namespace ramap {
namespace {

Eigen::Quaterniond RandomSmallRotation(std::mt19937& rng, double sigma_rad) {
  std::normal_distribution<double> normal(0.0, sigma_rad);
  const Eigen::Vector3d w(normal(rng), normal(rng), normal(rng));
  const double angle = w.norm();
  if (angle < 1e-15) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized();
}

Eigen::Matrix3d ProjectToRotation(const Eigen::Matrix3d& M) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

}  // namespace

SyntheticRotationGraph MakeSyntheticRotationGraph(const SyntheticRotationGraphOptions& options) {
  if (options.num_nodes < 2 || options.forward_neighbours < 1 || options.outlier_fraction < 0 ||
      options.outlier_fraction > 1) {
    throw std::invalid_argument("SyntheticRotationGraphOptions out of range");
  }
  std::mt19937 rng(options.seed);
  SyntheticRotationGraph synthetic;
  const int n = options.num_nodes;
  synthetic.true_rotations.resize(n);
  synthetic.true_rotations[0] = RandomRotation(rng);
  for (int k = 1; k < n; ++k) {
    synthetic.true_rotations[k] =
        (RandomSmallRotation(rng, options.rotation_step_deg * kDegToRad / std::sqrt(3.0)) *
         synthetic.true_rotations[k - 1])
            .normalized();
  }
  for (int k = 0; k < n; ++k) synthetic.graph.node_ids.push_back(static_cast<uint32_t>(k));

  std::set<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int d = 1; d <= options.forward_neighbours && i + d < n; ++d) pairs.insert({i, i + d});
  }
  const int max_gap = n - 1;
  if (options.loop_min_gap <= max_gap) {
    std::uniform_int_distribution<int> node(0, n - 1);
    int added = 0;
    for (int attempt = 0;
         added < options.num_loop_edges && attempt < 100 * (options.num_loop_edges + 1);
         ++attempt) {
      int i = node(rng);
      int j = node(rng);
      if (i > j) std::swap(i, j);
      if (j - i < options.loop_min_gap) continue;
      if (pairs.insert({i, j}).second) ++added;
    }
  }
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double noise_rad = options.noise_deg * kDegToRad;
  for (const auto& [i, j] : pairs) {
    RelativeRotationEdge edge;
    edge.i = static_cast<uint32_t>(i);
    edge.j = static_cast<uint32_t>(j);
    edge.weight = 1000.0 / (1.0 + (j - i));
    const bool outlier = uniform(rng) < options.outlier_fraction;
    if (outlier) {
      edge.R_ij = RandomRotation(rng);
    } else {
      const Eigen::Quaterniond exact =
          synthetic.true_rotations[j] * synthetic.true_rotations[i].conjugate();
      edge.R_ij = (RandomSmallRotation(rng, noise_rad) * exact).normalized();
    }
    synthetic.graph.edges.push_back(edge);
    synthetic.is_outlier.push_back(outlier);
  }
  return synthetic;
}

std::vector<double> AlignedRotationErrorsDeg(
    const std::vector<Eigen::Quaterniond>& estimated_rotations,
    const std::vector<Eigen::Quaterniond>& true_rotations, const std::vector<bool>& estimated) {
  const size_t n = std::min(estimated_rotations.size(), true_rotations.size());
  auto used = [&](size_t k) { return estimated.empty() || estimated[k]; };
  // R_est = R_true G  =>  G_k = R_true^T R_est; average the G_k.
  std::vector<double> weights(n, 1.0);
  Eigen::Quaterniond G = Eigen::Quaterniond::Identity();
  std::vector<double> errors;
  for (int pass = 0; pass < 3; ++pass) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < n; ++k) {
      if (!used(k)) continue;
      sum +=
          weights[k] * (true_rotations[k].conjugate() * estimated_rotations[k]).toRotationMatrix();
    }
    G = Eigen::Quaterniond(ProjectToRotation(sum));
    errors.clear();
    for (size_t k = 0; k < n; ++k) {
      if (!used(k)) continue;
      const Eigen::Quaterniond d = estimated_rotations[k].conjugate() * true_rotations[k] * G;
      const double angle = 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
      errors.push_back(angle * kRadToDeg);
      weights[k] = 1.0 / std::max(angle, 1e-9);  // L1-like reweighting against outlying nodes
    }
  }
  return errors;
}

}  // namespace ramap
