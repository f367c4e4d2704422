#include "ramap/averaging/window_alignment.h"

#include <ceres/ceres.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "ramap/util/disjoint_sets.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

// An image two windows share, with its centre in each: the residual s_a c_a + t_a - s_b c_b - t_b.
struct SharedImage {
  int window_a = 0, window_b = 0;
  Eigen::Vector3d center_a, center_b;
};

// [c, I]: the Jacobian of s c + t by (s, t).
Eigen::Matrix<double, 3, 4> PlacementJacobian(const Eigen::Vector3d& local_center) {
  Eigen::Matrix<double, 3, 4> jacobian;
  jacobian << local_center, Eigen::Matrix3d::Identity();
  return jacobian;
}

// The windows of each image, in increasing order.
std::map<uint32_t, std::vector<int>> WindowsOfImages(
    const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows) {
  std::map<uint32_t, std::vector<int>> windows_of;
  for (size_t w = 0; w < windows.size(); ++w) {
    for (const auto& [image_id, center] : windows[w]) {
      (void)center;
      windows_of[image_id].push_back(static_cast<int>(w));
    }
  }
  return windows_of;
}

// Every image in two windows (each pair of consecutive windows of an image in more).
std::vector<SharedImage> SharedImages(
    const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
    const std::map<uint32_t, std::vector<int>>& windows_of) {
  std::vector<SharedImage> shared;
  for (const auto& [image_id, in] : windows_of) {
    for (size_t k = 1; k < in.size(); ++k) {
      shared.push_back(
          {in[k - 1], in[k], windows[in[k - 1]].at(image_id), windows[in[k]].at(image_id)});
    }
  }
  return shared;
}

// Whether every non-empty window is tied to window 0 through windows sharing two images at
// distinct positions (which fixes their relative scale as well as their offset).
std::string UntiedWindowProblem(const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
                                const std::map<uint32_t, std::vector<int>>& windows_of) {
  DisjointSets sets(windows.size());
  // A union for each pair of windows tied by shared images.
  std::set<std::pair<int, int>> linked;
  for (const auto& [image_id, in] : windows_of) {
    (void)image_id;
    for (size_t k = 1; k < in.size(); ++k) linked.emplace(in[k - 1], in[k]);
  }
  for (const auto& [a, b] : linked) {
    if (WindowsTied(windows[a], windows[b])) sets.Union(a, b);
  }
  if (windows.empty() || windows.front().empty()) return "the first window has no centres";
  for (size_t w = 1; w < windows.size(); ++w) {
    if (!windows[w].empty() && sets.Find(w) != sets.Find(0)) {
      return "window " + std::to_string(w) + " shares fewer than two images with the others";
    }
  }
  return "";
}

// The placements' unknowns: (s, t) of each non-empty window but window 0, 4 columns each.
class PlacementColumns {
 public:
  explicit PlacementColumns(const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows)
      : first_(windows.size(), -1) {
    for (size_t w = 1; w < windows.size(); ++w) {
      if (!windows[w].empty()) first_[w] = 4 * num_windows_++;
    }
  }
  int size() const { return 4 * num_windows_; }
  int first(int window) const { return first_[window]; }  // -1: held (window 0) or empty

  // The residual of `image` at `x`.
  Eigen::Vector3d Residual(const SharedImage& image, const Eigen::VectorXd& x) const {
    return PlacementJacobian(image.center_a) * Placement(image.window_a, x) -
           PlacementJacobian(image.center_b) * Placement(image.window_b, x);
  }

  // (s, t) of `window` at `x`.
  Eigen::Vector4d Placement(int window, const Eigen::VectorXd& x) const {
    return first_[window] < 0 ? Eigen::Vector4d(1, 0, 0, 0)
                              : Eigen::Vector4d(x.segment<4>(first_[window]));
  }

 private:
  std::vector<int> first_;
  int num_windows_ = 0;
};

// The least-squares placements of the shared images' residuals, window 0 held.
Eigen::VectorXd SolveLeastSquares(const std::vector<SharedImage>& shared,
                                  const PlacementColumns& columns) {
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(columns.size());
  for (const SharedImage& image : shared) {
    // r = J_a p_a + J_b p_b; a held window's term is constant.
    const std::pair<int, Eigen::Matrix<double, 3, 4>> terms[2] = {
        {image.window_a, PlacementJacobian(image.center_a)},
        {image.window_b, -PlacementJacobian(image.center_b)}};
    Eigen::Vector3d constant = Eigen::Vector3d::Zero();
    for (const auto& [window, jacobian] : terms) {
      if (columns.first(window) < 0) constant += jacobian.col(0);  // s = 1, t = 0
    }
    for (const auto& [window_r, jacobian_r] : terms) {
      const int row = columns.first(window_r);
      if (row < 0) continue;
      rhs.segment<4>(row) -= jacobian_r.transpose() * constant;
      for (const auto& [window_c, jacobian_c] : terms) {
        const int col = columns.first(window_c);
        if (col < 0) continue;
        const Eigen::Matrix4d product = jacobian_r.transpose() * jacobian_c;
        for (int i = 0; i < 4; ++i) {
          for (int j = 0; j < 4; ++j) triplets.emplace_back(row + i, col + j, product(i, j));
        }
      }
    }
  }
  Eigen::SparseMatrix<double> normal(columns.size(), columns.size());
  normal.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) throw StageFailure("window alignment: factorisation failed");
  Eigen::VectorXd x = solver.solve(rhs);
  if (!x.allFinite()) throw StageFailure("window alignment: no finite solution");
  return x;
}

// The median residual of the shared images at `x`: the noise of the windows' own solutions.
double MedianSharedResidual(const std::vector<SharedImage>& shared, const PlacementColumns& columns,
                            const Eigen::VectorXd& x) {
  std::vector<double> residuals;
  for (const SharedImage& image : shared) residuals.push_back(columns.Residual(image, x).norm());
  if (residuals.empty()) return 0;
  std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
  return residuals[residuals.size() / 2];
}

// A shared image's disagreement, (s_a c_a + t_a - s_b c_b - t_b) / sqrt(s_a s_b) / sigma: in the
// windows' own units, so that shrinking every window does not lower it. A placement is
// (log s, t), which keeps the scale positive.
struct OverlapError {
  Eigen::Vector3d center_a, center_b;
  double sigma = 1;

  template <typename T>
  bool operator()(const T* placement_a, const T* placement_b, T* residual) const {
    const T scale_a = ceres::exp(placement_a[0]), scale_b = ceres::exp(placement_b[0]);
    const T norm = ceres::sqrt(scale_a * scale_b) * sigma;
    for (int k = 0; k < 3; ++k) {
      residual[k] = (scale_a * center_a[k] + placement_a[1 + k] - scale_b * center_b[k] -
                     placement_b[1 + k]) /
                    norm;
    }
    return true;
  }
};

// A cross direction's error: the unit vector from c_i to c_j minus d, over sigma (about the angle
// between them, in radians over sigma), which no scale changes.
struct CrossDirectionError {
  Eigen::Vector3d center_i, center_j, direction;
  double sigma = 1;

  template <typename T>
  bool operator()(const T* placement_i, const T* placement_j, T* residual) const {
    const T scale_i = ceres::exp(placement_i[0]), scale_j = ceres::exp(placement_j[0]);
    T baseline[3];
    for (int k = 0; k < 3; ++k) {
      baseline[k] =
          scale_j * center_j[k] + placement_j[1 + k] - scale_i * center_i[k] - placement_i[1 + k];
    }
    const T length = ceres::sqrt(baseline[0] * baseline[0] + baseline[1] * baseline[1] +
                                 baseline[2] * baseline[2] + T(1e-24));
    for (int k = 0; k < 3; ++k) residual[k] = (baseline[k] / length - direction[k]) / sigma;
    return true;
  }
};

// The placements as Ceres parameters (log s, t), from the least-squares ones.
std::vector<Eigen::Vector4d> CeresPlacements(size_t num_windows, const PlacementColumns& columns,
                                             const Eigen::VectorXd& x) {
  std::vector<Eigen::Vector4d> parameters(num_windows, Eigen::Vector4d::Zero());
  for (size_t w = 0; w < num_windows; ++w) {
    const int first = columns.first(static_cast<int>(w));
    if (first < 0) continue;
    if (!(x(first) > 0)) {
      throw StageFailure("window alignment: window " + std::to_string(w) +
                         " came out with a scale that is not positive");
    }
    parameters[w] << std::log(x(first)), x.segment<3>(first + 1);
  }
  return parameters;
}

// Adds a residual per usable cross direction (images in windows of their own; each image's first
// window stands for it).
void AddCrossDirections(const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
                        const std::map<uint32_t, std::vector<int>>& windows_of,
                        const std::vector<PairDirection>& cross_directions,
                        const WindowAlignmentOptions& options,
                        std::vector<Eigen::Vector4d>* parameters, ceres::Problem* problem) {
  // The usable directions' windows, and how many each pair of windows has.
  std::vector<std::pair<int, int>> between(cross_directions.size(), {-1, -1});
  std::map<std::pair<int, int>, int> count;
  for (size_t k = 0; k < cross_directions.size(); ++k) {
    const PairDirection& pair = cross_directions[k];
    const auto found1 = windows_of.find(pair.image_id1);
    const auto found2 = windows_of.find(pair.image_id2);
    if (found1 == windows_of.end() || found2 == windows_of.end()) continue;
    const int a = found1->second.front(), b = found2->second.front();
    if (a == b || !(pair.direction.norm() > 0)) continue;
    between[k] = {a, b};
    ++count[{std::min(a, b), std::max(a, b)}];
  }
  // Every stride-th direction of a pair of windows, at most max_directions_per_window_pair.
  std::map<std::pair<int, int>, int> seen;
  for (size_t k = 0; k < cross_directions.size(); ++k) {
    const auto [a, b] = between[k];
    if (a < 0) continue;
    const std::pair<int, int> key = {std::min(a, b), std::max(a, b)};
    const int stride = options.max_directions_per_window_pair > 0
                           ? (count[key] + options.max_directions_per_window_pair - 1) /
                                 options.max_directions_per_window_pair
                           : 1;
    if (seen[key]++ % stride != 0) continue;
    const PairDirection& pair = cross_directions[k];
    auto* error =
        new CrossDirectionError{windows[a].at(pair.image_id1), windows[b].at(pair.image_id2),
                                pair.direction.normalized(), options.direction_sigma_rad};
    problem->AddResidualBlock(new ceres::AutoDiffCostFunction<CrossDirectionError, 3, 4, 4>(error),
                              new ceres::HuberLoss(1.0), (*parameters)[a].data(),
                              (*parameters)[b].data());
  }
}

// The placements of Ceres parameters (log s, t).
std::vector<WindowPlacement> Placements(const std::vector<Eigen::Vector4d>& parameters) {
  std::vector<WindowPlacement> placements(parameters.size());
  for (size_t w = 0; w < parameters.size(); ++w) {
    placements[w].scale = std::exp(parameters[w](0));
    placements[w].translation = parameters[w].tail<3>();
  }
  return placements;
}

}  // namespace

bool WindowsTied(const std::map<uint32_t, Eigen::Vector3d>& a,
                 const std::map<uint32_t, Eigen::Vector3d>& b) {
  const Eigen::Vector3d* first = nullptr;
  for (const auto& [image_id, center] : a) {
    if (!b.count(image_id)) continue;
    if (!first) {
      first = &center;
    } else if ((center - *first).norm() > 1e-9) {
      return true;
    }
  }
  return false;
}

std::vector<WindowPlacement> AlignWindows(
    const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
    const std::vector<PairDirection>& cross_directions, const WindowAlignmentOptions& options) {
  const std::map<uint32_t, std::vector<int>> windows_of = WindowsOfImages(windows);
  const std::string problem_text = UntiedWindowProblem(windows, windows_of);
  if (!problem_text.empty()) throw StageFailure("window alignment: " + problem_text);
  // 1. The overlaps alone by least squares: a chain that carries the scale window to window.
  const std::vector<SharedImage> shared = SharedImages(windows, windows_of);
  const PlacementColumns columns(windows);
  const Eigen::VectorXd x = SolveLeastSquares(shared, columns);
  std::vector<Eigen::Vector4d> parameters = CeresPlacements(windows.size(), columns, x);
  if (options.max_num_iterations > 0 && !cross_directions.empty()) {
    // 2. With the cross directions: Huber losses on both kinds of residual, each in its own
    // noise (the overlaps' from their least-squares residuals).
    const double overlap_sigma = std::max(1e-9, MedianSharedResidual(shared, columns, x));
    ceres::Problem problem;
    for (const SharedImage& image : shared) {
      auto* error = new OverlapError{image.center_a, image.center_b,
                                     options.huber_overlap_residuals * overlap_sigma};
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OverlapError, 3, 4, 4>(error),
                               new ceres::HuberLoss(1.0), parameters[image.window_a].data(),
                               parameters[image.window_b].data());
    }
    AddCrossDirections(windows, windows_of, cross_directions, options, &parameters, &problem);
    if (!problem.HasParameterBlock(parameters[0].data())) return Placements(parameters);
    problem.SetParameterBlockConstant(parameters[0].data());
    ceres::Solver::Options solver_options;
    solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver_options.max_num_iterations = options.max_num_iterations;
    solver_options.num_threads = options.num_threads;
    solver_options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    if (!summary.IsSolutionUsable()) throw StageFailure("window alignment: " + summary.message);
  }
  return Placements(parameters);
}

}  // namespace ramap
