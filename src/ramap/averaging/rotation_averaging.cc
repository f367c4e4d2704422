#include "ramap/averaging/rotation_averaging.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "ramap/geometry/rotation.h"
#include "ramap/graph/cycle_consistency.h"
#include "ramap/graph/fiedler.h"
#include "ramap/util/option_check.h"
#include "ramap/util/run_observer.h"
#include "ramap/util/statistics.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

Eigen::Vector3d LogQ(const Eigen::Quaterniond& q) {
  double w = q.w();
  Eigen::Vector3d v = q.vec();
  if (w < 0.0) {
    w = -w;
    v = -v;
  }
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v / std::max(w, 1e-300);
  return v * (2.0 * std::atan2(s, w) / s);
}

Eigen::Quaterniond ExpQ(const Eigen::Vector3d& w) {
  const double theta = w.norm();
  if (theta < 1e-12)
    return Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  const double half = 0.5 * theta;
  const Eigen::Vector3d v = w * (std::sin(half) / theta);
  return Eigen::Quaterniond(std::cos(half), v.x(), v.y(), v.z());
}

double AngleOf(const Eigen::Quaterniond& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// The error rotation R_j^T R_ij R_i of an edge (identity when consistent).
Eigen::Quaterniond EdgeError(const RelativeRotationEdge& edge, const Eigen::Quaterniond& R_i,
                             const Eigen::Quaterniond& R_j) {
  return R_j.conjugate() * edge.R_ij * R_i;
}

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// A late IRLS step converges in a few conjugate-gradient iterations, but a step that reweights
// much gives up after a few, wasting them: below this many iterations' worth of a factorisation
// the attempts cost more than they save. A long drive's whole graph, whose loops fill its factor,
// is far above it and gains most; the SE-Sync graphs, the synthetic 10,000 cameras and the
// keyframe windows are below it, and a lower bound made them slower (BENCHMARKS.md, "Scale").
constexpr int kMinPcgIterationsPerFactorization = 10;

// The reweighted tangent-space least-squares problem on a fixed edge set:
//   min sum_e c_e || log(R_j^T R_ij R_i) - (w_j - w_i) ||^2,  w_pinned = 0,
// whose normal matrix is the c-weighted Laplacian (x) I_3. The grounded Laplacian's pattern is
// built and analysed by CHOLMOD once; every iteration refills its values and refactorises, or,
// when the factor is costly enough, first tries conjugate gradients preconditioned by the last one.
class TangentIrls {
 public:
  TangentIrls(const RotationGraph& graph, const std::vector<int>& edge_a,
              const std::vector<int>& edge_b, const std::vector<size_t>& edges,
              const std::vector<bool>& active_nodes, const std::vector<double>& base_weights,
              const PreconditionedCgOptions& pcg)
      : graph_(graph),
        edge_a_(edge_a),
        edge_b_(edge_b),
        edges_(edges),
        base_weights_(base_weights),
        pcg_(pcg) {
    const int n = static_cast<int>(active_nodes.size());
    // Hold the node of largest degree fixed: best conditioned choice of gauge.
    std::vector<int> degree(n, 0);
    for (size_t e : edges_) {
      ++degree[edge_a_[e]];
      ++degree[edge_b_[e]];
    }
    pinned_ = -1;
    for (int k = 0; k < n; ++k) {
      if (active_nodes[k] && (pinned_ < 0 || degree[k] > degree[pinned_])) pinned_ = k;
    }
    unknown_.assign(n, -1);
    num_unknowns_ = 0;
    for (int k = 0; k < n; ++k) {
      if (active_nodes[k] && k != pinned_) unknown_[k] = num_unknowns_++;
    }
    if (num_unknowns_ == 0) return;
    // Lower-triangle pattern: diagonal of every unknown, one off-diagonal entry per edge.
    std::vector<Eigen::Triplet<double, int>> triplets;
    triplets.reserve(num_unknowns_ + edges_.size());
    for (int u = 0; u < num_unknowns_; ++u) triplets.emplace_back(u, u, 0.0);
    for (size_t e : edges_) {
      const int ua = unknown_[edge_a_[e]];
      const int ub = unknown_[edge_b_[e]];
      if (ua >= 0 && ub >= 0) triplets.emplace_back(std::max(ua, ub), std::min(ua, ub), 0.0);
    }
    matrix_.resize(num_unknowns_, num_unknowns_);
    matrix_.setFromTriplets(triplets.begin(), triplets.end());
    matrix_.makeCompressed();
    auto slot = [&](int row, int col) {
      const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
      const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
      return static_cast<int>(std::lower_bound(begin, end, row) - matrix_.innerIndexPtr());
    };
    diag_slot_.resize(num_unknowns_);
    for (int u = 0; u < num_unknowns_; ++u) diag_slot_[u] = slot(u, u);
    off_slot_.resize(edges_.size(), -1);
    for (size_t k = 0; k < edges_.size(); ++k) {
      const int ua = unknown_[edge_a_[edges_[k]]];
      const int ub = unknown_[edge_b_[edges_[k]]];
      if (ua >= 0 && ub >= 0) off_slot_[k] = slot(std::max(ua, ub), std::min(ua, ub));
    }
    // Laplacians of view graphs factor with little fill; the simplicial LL^T avoids the BLAS
    // threading overhead of the supernodal path (measured faster on the 10,000-camera benchmark).
    solver_.setMode(Eigen::CholmodSimplicialLLt);
    solver_.analyzePattern(matrix_);
    iterations_per_factorization_ = IterationsPerFactorization();
  }

  // Runs at most max_iterations relinearisations, updating `rotations` in place. At each, the
  // linear problem in the tangent space is solved by `inner_iterations` reweighted least-squares
  // steps (1: plain IRLS on the nonlinear problem); the weight of an edge is weight_of(residual
  // angle in radians). Returns the number of relinearisations done.
  int Run(const std::function<double(double)>& weight_of, int max_iterations,
          double rms_tolerance_rad, std::vector<Eigen::Quaterniond>* rotations,
          int inner_iterations = 1) {
    if (num_unknowns_ == 0) return 0;
    std::vector<Eigen::Quaterniond>& R = *rotations;
    Eigen::MatrixXd rhs(num_unknowns_, 3);
    Eigen::MatrixXd step = Eigen::MatrixXd::Zero(num_unknowns_, 3);
    std::vector<Eigen::Vector3d> residuals(edges_.size());
    std::vector<double> weights(edges_.size());
    auto step_of = [&](int node) -> Eigen::Vector3d {
      const int u = unknown_[node];
      return u < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(step.row(u).transpose());
    };
    int iteration = 0;
    while (iteration < max_iterations) {
      ++iteration;
      CheckForStop();
      for (size_t k = 0; k < edges_.size(); ++k) {
        const size_t e = edges_[k];
        residuals[k] = LogQ(EdgeError(graph_.edges[e], R[edge_a_[e]], R[edge_b_[e]]));
      }
      step.setZero();
      for (int inner = 0; inner < inner_iterations; ++inner) {
        double max_weight = 0.0;
        for (size_t k = 0; k < edges_.size(); ++k) {
          const size_t e = edges_[k];
          const Eigen::Vector3d r = residuals[k] - (step_of(edge_b_[e]) - step_of(edge_a_[e]));
          weights[k] = weight_of(r.norm()) * base_weights_[e];
          max_weight = std::max(max_weight, weights[k]);
        }
        // A floor keeps the system positive definite when every edge of a node is an outlier.
        const double floor = 1e-9 * std::max(max_weight, 1e-300);
        double* values = matrix_.valuePtr();
        std::fill(values, values + matrix_.nonZeros(), 0.0);
        rhs.setZero();
        for (size_t k = 0; k < edges_.size(); ++k) {
          const size_t e = edges_[k];
          const double c = std::max(weights[k], floor);
          const int ua = unknown_[edge_a_[e]];
          const int ub = unknown_[edge_b_[e]];
          // c ||phi - (w_b - w_a)||^2: contributes +c phi to row b and -c phi to row a.
          if (ua >= 0) {
            values[diag_slot_[ua]] += c;
            rhs.row(ua) -= c * residuals[k].transpose();
          }
          if (ub >= 0) {
            values[diag_slot_[ub]] += c;
            rhs.row(ub) += c * residuals[k].transpose();
          }
          if (off_slot_[k] >= 0) values[off_slot_[k]] -= c;
        }
        Eigen::MatrixXd next = step;
        if (!SolveWithLastFactor(rhs, &next)) {
          solver_.factorize(matrix_);
          if (solver_.info() != Eigen::Success) {
            throw std::runtime_error("rotation averaging: CHOLMOD factorisation failed");
          }
          ++num_factorizations_;
          next = solver_.solve(rhs);
        }
        const double change = (next - step).norm() / std::sqrt(double(num_unknowns_));
        step.swap(next);
        if (change < rms_tolerance_rad) break;
      }
      for (size_t node = 0; node < unknown_.size(); ++node) {
        const int u = unknown_[node];
        if (u >= 0) R[node] = (R[node] * ExpQ(step.row(u).transpose())).normalized();
      }
      if (step.norm() / std::sqrt(double(num_unknowns_)) < rms_tolerance_rad) break;
    }
    return iteration;
  }

  void set_pcg_options(const PreconditionedCgOptions& pcg) { pcg_ = pcg; }
  int num_factorizations() const { return num_factorizations_; }

 private:
  // The step's equations by conjugate gradients, preconditioned by the last factorisation and
  // started from *solution (PreconditionedCgOptions); false when there is no factor yet or they
  // do not converge in time.
  bool SolveWithLastFactor(const Eigen::MatrixXd& rhs, Eigen::MatrixXd* solution) {
    if (num_factorizations_ == 0) return false;
    if (iterations_per_factorization_ < kMinPcgIterationsPerFactorization) return false;
    PreconditionedCgOptions pcg = pcg_;
    pcg.max_iterations = std::min(pcg.max_iterations, iterations_per_factorization_);
    const auto apply = [&](const Eigen::MatrixXd& x) -> Eigen::MatrixXd {
      return matrix_.selfadjointView<Eigen::Lower>() * x;
    };
    const auto precondition = [&](const Eigen::MatrixXd& r) -> Eigen::MatrixXd {
      return solver_.solve(r);
    };
    return SolveByPreconditionedCg(apply, precondition, rhs, pcg, solution);
  }

  // How many conjugate-gradient iterations cost as many flops as a factorisation (CHOLMOD's count
  // from the analysis): an iteration applies the matrix and solves with the factor, for three
  // columns. Conjugate gradients are tried within that budget, and only when it is at least
  // kMinPcgIterationsPerFactorization.
  int IterationsPerFactorization() {
    const cholmod_common& common = solver_.cholmod();
    const double iteration_flops =
        3.0 * (4.0 * common.lnz + 4.0 * static_cast<double>(matrix_.nonZeros()));
    if (!(common.fl > 0) || !(iteration_flops > 0)) return 0;
    return static_cast<int>(std::min(1e6, std::floor(common.fl / iteration_flops)));
  }

  const RotationGraph& graph_;
  const std::vector<int>& edge_a_;
  const std::vector<int>& edge_b_;
  std::vector<size_t> edges_;
  const std::vector<double>& base_weights_;
  int pinned_ = -1;
  std::vector<int> unknown_;
  int num_unknowns_ = 0;
  SparseMatrix matrix_;
  std::vector<int> diag_slot_;
  std::vector<int> off_slot_;
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> solver_;
  PreconditionedCgOptions pcg_;
  int iterations_per_factorization_ = 0;
  int num_factorizations_ = 0;
};

// The conjugate gradients' options of `options`.
PreconditionedCgOptions PcgOptions(const RotationAveragingOptions& options) {
  PreconditionedCgOptions pcg;
  pcg.max_iterations = options.max_pcg_iterations;
  pcg.tolerance = options.pcg_tolerance;
  return pcg;
}

std::function<double(double)> RobustWeight(const RotationAveragingOptions& options) {
  const double sigma = options.sigma_deg * kDegToRad;
  const double min_residual = options.l1_min_residual_deg * kDegToRad;
  if (options.loss == RobustLoss::kL1Half) {
    // rho = |r|^(1/2): rho'(r) / r = r^(-3/2) / 2.
    return [min_residual](double r) { return std::pow(std::max(r, min_residual), -1.5); };
  }
  // rho = r^2 / (r^2 + sigma^2): rho'(r) / r = 2 sigma^2 / (r^2 + sigma^2)^2 (normalised to 1 at
  // 0).
  return [sigma](double r) {
    const double s = sigma * sigma / (r * r + sigma * sigma);
    return s * s;
  };
}

// rho = 8 sin^2(r / 2) = ||I - exp([r]_x)||_F^2, the chordal cost of an edge: rho'(r) / r is
// proportional to sin(r) / r. Fixed points of this IRLS are stationary points of the chordal cost
// because the gradient of |log(exp(-w) Q)|^2 / 2 at w = 0 is exactly -log(Q).
double ChordalWeight(double r) { return r < 1e-8 ? 1.0 : std::sin(r) / r; }

struct IndexedEdges {
  std::vector<int> a;  // node position of edge.i
  std::vector<int> b;  // node position of edge.j
};

IndexedEdges IndexEdges(const RotationGraph& graph) {
  const auto index = NodeIndex(graph);
  IndexedEdges indexed;
  indexed.a.reserve(graph.edges.size());
  indexed.b.reserve(graph.edges.size());
  for (const RelativeRotationEdge& edge : graph.edges) {
    indexed.a.push_back(index.at(edge.i));
    indexed.b.push_back(index.at(edge.j));
  }
  return indexed;
}

// Active nodes = the largest component of the kept edges among `candidates`; kept edges leaving
// it are marked disconnected.
void RestrictToLargestComponent(const RotationGraph& graph, const IndexedEdges& indexed, int round,
                                RotationAveragingResult* result, std::vector<bool>* keep) {
  std::vector<bool> usable(*keep);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (usable[e] && (!result->estimated[indexed.a[e]] || !result->estimated[indexed.b[e]])) {
      usable[e] = false;
    }
  }
  const std::vector<int> labels = ConnectedComponents(graph, usable);
  for (size_t k = 0; k < labels.size(); ++k) {
    if (labels[k] != 0) result->estimated[k] = false;
  }
  // A single isolated node would otherwise count as component 0 of an edgeless graph.
  std::vector<int> degree = NodeDegrees(graph, usable);
  for (size_t k = 0; k < degree.size(); ++k) {
    if (degree[k] == 0) result->estimated[k] = false;
  }
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!(*keep)[e]) continue;
    if (!result->estimated[indexed.a[e]] || !result->estimated[indexed.b[e]]) {
      (*keep)[e] = false;
      result->edge_status[e] = EdgeStatus::kPrunedDisconnected;
      PrunedEdge pruned;
      pruned.edge_index = e;
      pruned.round = round;
      pruned.residual_deg = std::numeric_limits<double>::quiet_NaN();
      pruned.reason = EdgeStatus::kPrunedDisconnected;
      result->pruned_edges.push_back(pruned);
    }
  }
}

std::vector<size_t> KeptEdges(const std::vector<bool>& keep) {
  std::vector<size_t> edges;
  for (size_t e = 0; e < keep.size(); ++e) {
    if (keep[e]) edges.push_back(e);
  }
  return edges;
}

int MaxDegree(const RotationGraph& graph, const std::vector<bool>& keep) {
  const std::vector<int> degree = NodeDegrees(graph, keep);
  return degree.empty() ? 0 : *std::max_element(degree.begin(), degree.end());
}

// The Eriksson et al. bound of the kept graph restricted to its estimated nodes (radians).
double KeptGraphBound(const RotationGraph& graph, const std::vector<bool>& keep,
                      const std::vector<bool>& estimated, double* lambda2, int* max_degree) {
  RotationGraph sub;
  std::vector<bool> sub_keep;
  for (size_t k = 0; k < graph.node_ids.size(); ++k) {
    if (estimated[k]) sub.node_ids.push_back(graph.node_ids[k]);
  }
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (keep[e]) sub.edges.push_back(graph.edges[e]);
  }
  *lambda2 = FiedlerValue(sub, /*weighted=*/false);
  *max_degree = MaxDegree(sub, {});
  return StrongDualityResidualBound(*lambda2, *max_degree);
}

}  // namespace

void RotationAveragingOptions::Check() const {
  CheckOptionValues(RotationAveragingOptionTable(), *this);
  // The settings no command line option reaches.
  const std::string s = "RotationAveragingOptions::";
  CheckOption(l1_inner_iterations >= 1, s + "l1_inner_iterations", ">= 1", l1_inner_iterations);
  CheckOption(l1_step_tolerance_deg >= 0.0, s + "l1_step_tolerance_deg", ">= 0",
              l1_step_tolerance_deg);
  CheckOption(l1_min_residual_deg > 0.0, s + "l1_min_residual_deg", "> 0", l1_min_residual_deg);
  CheckOption(irls_step_tolerance_deg >= 0.0, s + "irls_step_tolerance_deg", ">= 0",
              irls_step_tolerance_deg);
  CheckOption(pcg_tolerance > 0 && pcg_tolerance < 1, s + "pcg_tolerance", "in (0, 1)",
              pcg_tolerance);
  CheckOption(max_certificate_iterations >= 0, s + "max_certificate_iterations", ">= 0",
              max_certificate_iterations);
  CheckOption(certificate_step_tolerance_deg >= 0.0, s + "certificate_step_tolerance_deg", ">= 0",
              certificate_step_tolerance_deg);
}

double EdgeResidualDeg(const RelativeRotationEdge& edge, const Eigen::Quaterniond& R_i,
                       const Eigen::Quaterniond& R_j) {
  return AngleOf(EdgeError(edge, R_i, R_j)) * kRadToDeg;
}

double ChordalCost(const RotationGraph& graph, const std::vector<Eigen::Quaterniond>& rotations,
                   const std::vector<bool>& keep, const std::vector<bool>& estimated) {
  const IndexedEdges indexed = IndexEdges(graph);
  double cost = 0.0;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep.empty() && !keep[e]) continue;
    const int a = indexed.a[e];
    const int b = indexed.b[e];
    if (!estimated.empty() && (!estimated[a] || !estimated[b])) continue;
    const double half = 0.5 * AngleOf(EdgeError(graph.edges[e], rotations[a], rotations[b]));
    cost += 8.0 * std::sin(half) * std::sin(half);
  }
  return cost;
}

namespace {

// Every edge's residual (deg) under the current rotations; NaN where a node is not estimated.
void ComputeEdgeResiduals(const RotationGraph& graph, const IndexedEdges& indexed,
                          RotationAveragingResult* result) {
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    const int a = indexed.a[e];
    const int b = indexed.b[e];
    result->edge_residuals_deg[e] =
        result->estimated[a] && result->estimated[b]
            ? EdgeResidualDeg(graph.edges[e], result->rotations[a], result->rotations[b])
            : std::numeric_limits<double>::quiet_NaN();
  }
}

// A node most of whose kept edges exceed the threshold is more likely mis-estimated than
// surrounded by outliers; pruning would strand it on whichever edges happen to agree with its
// wrong estimate. Such nodes (at least three kept edges) are suspect.
std::vector<bool> SuspectNodes(const RotationGraph& graph, const IndexedEdges& indexed,
                               const std::vector<bool>& keep, const RotationAveragingResult& result,
                               double threshold_deg) {
  const size_t n = graph.node_ids.size();
  std::vector<int> degree(n, 0);
  std::vector<int> above(n, 0);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep[e]) continue;
    const bool high = result.edge_residuals_deg[e] > threshold_deg;
    for (int node : {indexed.a[e], indexed.b[e]}) {
      ++degree[node];
      above[node] += high;
    }
  }
  std::vector<bool> suspect(n, false);
  for (size_t k = 0; k < n; ++k) suspect[k] = degree[k] >= 3 && 2 * above[k] > degree[k];
  return suspect;
}

// Re-initialises each suspect node from the consensus of its neighbours (the candidate rotation
// most of the others agree with). A node whose neighbours agree with its current estimate is
// right after all and is no longer suspect: its edges are pruned as usual. True when a node moved.
bool ReinitializeSuspectNodes(const RotationGraph& graph, const IndexedEdges& indexed,
                              const std::vector<bool>& keep, double threshold_deg,
                              std::vector<bool>* suspect, RotationAveragingResult* result) {
  const size_t n = graph.node_ids.size();
  std::vector<std::vector<Eigen::Quaterniond>> candidates(n);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep[e]) continue;
    const int a = indexed.a[e];
    const int b = indexed.b[e];
    const Eigen::Quaterniond& R_ab = graph.edges[e].R_ij;
    if ((*suspect)[a]) candidates[a].push_back(R_ab.conjugate() * result->rotations[b]);
    if ((*suspect)[b]) candidates[b].push_back(R_ab * result->rotations[a]);
  }
  const double agree_rad = threshold_deg * kDegToRad;
  bool changed = false;
  for (size_t k = 0; k < n; ++k) {
    if (!(*suspect)[k]) continue;
    int best_support = -1;
    Eigen::Quaterniond best = result->rotations[k];
    for (const Eigen::Quaterniond& candidate : candidates[k]) {
      int support = 0;
      for (const Eigen::Quaterniond& other : candidates[k]) {
        support += candidate.angularDistance(other) < agree_rad;
      }
      if (support > best_support) {
        best_support = support;
        best = candidate;
      }
    }
    if (best.angularDistance(result->rotations[k]) < agree_rad) {
      (*suspect)[k] = false;
      continue;
    }
    result->rotations[k] = best.normalized();
    result->reinitialized_nodes.push_back(graph.node_ids[k]);
    changed = true;
  }
  return changed;
}

// Prunes every kept edge whose residual exceeds the threshold, but the edges of suspect nodes.
// True when an edge was pruned.
bool PruneEdgesAbove(double threshold_deg, int round, const IndexedEdges& indexed,
                     const std::vector<bool>& suspect, std::vector<bool>* keep,
                     RotationAveragingResult* result) {
  bool changed = false;
  for (size_t e = 0; e < keep->size(); ++e) {
    if (!(*keep)[e] || !(result->edge_residuals_deg[e] > threshold_deg)) continue;
    if (suspect[indexed.a[e]] || suspect[indexed.b[e]]) continue;
    (*keep)[e] = false;
    result->edge_status[e] = EdgeStatus::kPrunedResidual;
    PrunedEdge pruned;
    pruned.edge_index = e;
    pruned.round = round;
    pruned.residual_deg = result->edge_residuals_deg[e];
    pruned.threshold_deg = threshold_deg;
    pruned.reason = EdgeStatus::kPrunedResidual;
    result->pruned_edges.push_back(pruned);
    changed = true;
  }
  return changed;
}

// kAdaptive's threshold: adaptive_multiplier times the kept edges' median residual, within
// [adaptive_min_deg, alpha_max_deg].
double AdaptiveThresholdDeg(const std::vector<bool>& keep, const RotationAveragingResult& result,
                            const RotationAveragingOptions& options) {
  std::vector<double> residuals;
  for (size_t e = 0; e < keep.size(); ++e) {
    if (keep[e] && std::isfinite(result.edge_residuals_deg[e])) {
      residuals.push_back(result.edge_residuals_deg[e]);
    }
  }
  if (residuals.empty()) return options.alpha_max_deg;
  return std::clamp(options.adaptive_multiplier * Median(std::move(residuals)),
                    options.adaptive_min_deg, options.alpha_max_deg);
}

// The robust weights' IRLS, as the pruning rounds and the first run use it.
struct RobustIrls {
  std::function<double(double)> weight;
  int max_iterations = 0;
  double tolerance_rad = 0;
  const std::vector<double>& base_weights;
};

// Pruning rounds: edges above the threshold (the adaptive one, alpha_max_deg, or the
// strong-duality bound) are pruned, suspect nodes re-initialised, and the robust IRLS run again on
// the largest component, until a round changes nothing or max_pruning_rounds have run.
void RunPruningRounds(const RotationGraph& graph, const IndexedEdges& indexed,
                      const RotationAveragingOptions& options, const RobustIrls& irls,
                      std::vector<bool>* keep, RotationAveragingResult* result) {
  const size_t n = graph.node_ids.size();
  double adaptive_deg = -1.0;  // kAdaptive: from the first round's residuals, then held
  for (int round = 1; round <= options.max_pruning_rounds; ++round) {
    ComputeEdgeResiduals(graph, indexed, result);
    double threshold_deg = options.alpha_max_deg;
    if (options.pruning_mode == PruningThresholdMode::kStrongDualityBound) {
      double lambda2 = 0.0;
      int max_degree = 0;
      threshold_deg =
          KeptGraphBound(graph, *keep, result->estimated, &lambda2, &max_degree) * kRadToDeg;
    } else if (options.pruning_mode == PruningThresholdMode::kAdaptive) {
      if (adaptive_deg < 0) adaptive_deg = AdaptiveThresholdDeg(*keep, *result, options);
      threshold_deg = adaptive_deg;
    }
    std::vector<bool> suspect(n, false);
    if (options.reinitialize_suspect_nodes &&
        options.pruning_mode != PruningThresholdMode::kStrongDualityBound) {
      suspect = SuspectNodes(graph, indexed, *keep, *result, threshold_deg);
    }
    bool changed = false;
    if (std::find(suspect.begin(), suspect.end(), true) != suspect.end()) {
      changed = ReinitializeSuspectNodes(graph, indexed, *keep, threshold_deg, &suspect, result);
    }
    changed = PruneEdgesAbove(threshold_deg, round, indexed, suspect, keep, result) || changed;
    if (!changed) break;
    ++result->pruning_rounds;
    RestrictToLargestComponent(graph, indexed, round, result, keep);
    TangentIrls solver(graph, indexed.a, indexed.b, KeptEdges(*keep), result->estimated,
                       irls.base_weights, PcgOptions(options));
    result->irls_iterations +=
        solver.Run(irls.weight, irls.max_iterations, irls.tolerance_rad, &result->rotations);
    result->factorizations += solver.num_factorizations();
  }
  ComputeEdgeResiduals(graph, indexed, result);
}

// The global optimality certificate on the kept graph: the chordal optimum from the robust
// solution, its largest residual against the strong-duality bound of the kept graph.
void ComputeCertificate(const RotationGraph& graph, const IndexedEdges& indexed,
                        const std::vector<bool>& keep, const RotationAveragingOptions& options,
                        RotationAveragingResult* result) {
  RotationCertificate& certificate = result->certificate;
  certificate.computed = true;
  certificate.bound_deg = KeptGraphBound(graph, keep, result->estimated, &certificate.fiedler_value,
                                         &certificate.max_degree) *
                          kRadToDeg;
  certificate.rotations = result->rotations;
  if (options.certificate_cycle_check) {
    certificate.cycle_residual_lower_bound_deg =
        TriangleCycleResidualBound(graph, keep, result->estimated, certificate.bound_deg)
            .residual_lower_bound_deg;
    certificate.refinement_skipped =
        certificate.cycle_residual_lower_bound_deg > certificate.bound_deg;
  }
  if (!certificate.refinement_skipped) {
    const std::vector<double> unit_weights(graph.edges.size(), 1.0);
    TangentIrls chordal(graph, indexed.a, indexed.b, KeptEdges(keep), result->estimated,
                        unit_weights, PcgOptions(options));
    certificate.iterations =
        chordal.Run(ChordalWeight, options.max_certificate_iterations,
                    options.certificate_step_tolerance_deg * kDegToRad, &certificate.rotations);
  }
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep[e]) continue;
    const int a = indexed.a[e];
    const int b = indexed.b[e];
    certificate.max_residual_deg = std::max(
        certificate.max_residual_deg,
        EdgeResidualDeg(graph.edges[e], certificate.rotations[a], certificate.rotations[b]));
    certificate.max_robust_residual_deg =
        std::max(certificate.max_robust_residual_deg, result->edge_residuals_deg[e]);
  }
  certificate.certified = !certificate.refinement_skipped && certificate.bound_deg > 0.0 &&
                          certificate.max_residual_deg <= certificate.bound_deg;
}

// The edges' inlier counts, each saturated as RotationAveragingOptions::edge_weight_saturation
// says.
std::vector<double> SaturatedEdgeWeights(const RotationGraph& graph,
                                         const RotationAveragingOptions& options) {
  std::vector<double> weights(graph.edges.size());
  for (size_t e = 0; e < graph.edges.size(); ++e) weights[e] = graph.edges[e].weight;
  if (options.edge_weight_saturation <= 0 || weights.empty()) return weights;
  const double saturation = options.edge_weight_saturation * Median(weights);
  if (!(saturation > 0)) return weights;
  for (double& w : weights) w /= 1.0 + w / saturation;
  return weights;
}

}  // namespace

RotationAveragingResult AverageRotationsFrom(const RotationGraph& graph,
                                             const std::vector<Eigen::Quaterniond>& initial,
                                             const std::vector<bool>& initial_known,
                                             const RotationAveragingOptions& options) {
  options.Check();
  Timer total_timer;
  Timer timer;
  const size_t n = graph.node_ids.size();
  if (initial.size() != n || initial_known.size() != n) {
    throw std::invalid_argument("AverageRotationsFrom: one initial rotation per node expected");
  }
  const IndexedEdges indexed = IndexEdges(graph);
  RotationAveragingResult result;
  result.node_ids = graph.node_ids;
  result.edge_status.assign(graph.edges.size(), EdgeStatus::kKept);
  result.edge_residuals_deg.assign(graph.edges.size(), std::numeric_limits<double>::quiet_NaN());

  // Initialisation: chain along the maximum spanning tree from the known nodes.
  result.rotations = initial;
  std::vector<bool> known = initial_known;
  PropagateAlongTree(graph, MaximumSpanningTree(graph), &result.rotations, &known);
  result.estimated = known;
  std::vector<bool> keep(graph.edges.size(), true);
  RestrictToLargestComponent(graph, indexed, 0, &result, &keep);
  result.timings.init = timer.ElapsedSeconds();

  std::vector<double> base_weights(graph.edges.size(), 1.0);
  if (options.use_edge_weights) base_weights = SaturatedEdgeWeights(graph, options);

  // L1RA, then the first robust IRLS run.
  timer.Restart();
  // L1 reweighting moves the weights far at every step, so an old factor preconditions poorly
  // there (slower than refactorising on a drive; BENCHMARKS.md, "Scale"): PCG only from IRLS.
  TangentIrls solver(graph, indexed.a, indexed.b, KeptEdges(keep), result.estimated, base_weights,
                     PreconditionedCgOptions{0});
  const double l1_floor = options.l1_min_residual_deg * kDegToRad;
  result.l1_iterations = solver.Run(
      [l1_floor](double r) { return 1.0 / std::max(r, l1_floor); }, options.max_l1_iterations,
      options.l1_step_tolerance_deg * kDegToRad, &result.rotations, options.l1_inner_iterations);
  result.timings.l1 = timer.ElapsedSeconds();
  timer.Restart();
  solver.set_pcg_options(PcgOptions(options));
  const RobustIrls irls{RobustWeight(options), options.max_irls_iterations,
                        options.irls_step_tolerance_deg * kDegToRad, base_weights};
  result.irls_iterations =
      solver.Run(irls.weight, irls.max_iterations, irls.tolerance_rad, &result.rotations);
  result.factorizations = solver.num_factorizations();
  result.timings.irls = timer.ElapsedSeconds();

  timer.Restart();
  RunPruningRounds(graph, indexed, options, irls, &keep, &result);
  result.timings.pruning = timer.ElapsedSeconds();

  if (options.compute_certificate) {
    timer.Restart();
    ComputeCertificate(graph, indexed, keep, options, &result);
    result.timings.certificate = timer.ElapsedSeconds();
  }
  result.timings.total = total_timer.ElapsedSeconds();
  return result;
}

RotationAveragingResult AverageRotations(const RotationGraph& graph,
                                         const RotationAveragingOptions& options) {
  const size_t n = graph.node_ids.size();
  return AverageRotationsFrom(graph,
                              std::vector<Eigen::Quaterniond>(n, Eigen::Quaterniond::Identity()),
                              std::vector<bool>(n, false), options);
}

RotationAveragingResult AverageRotationsInWindows(const RotationGraph& graph,
                                                  const Keyframes& keyframes,
                                                  const RotationAveragingOptions& options) {
  options.Check();
  Timer timer;
  const auto index = NodeIndex(graph);
  const IndexedEdges indexed = IndexEdges(graph);
  const size_t n = graph.node_ids.size();
  std::vector<Eigen::Quaterniond> stitched(n, Eigen::Quaterniond::Identity());
  std::vector<bool> known(n, false);
  RotationAveragingOptions local_options = options;
  local_options.compute_certificate = false;

  for (const KeyframeWindow& window : keyframes.windows) {
    std::vector<bool> in_window(n, false);
    for (uint32_t id : window.frames) {
      const auto it = index.find(id);
      if (it != index.end()) in_window[it->second] = true;
    }
    std::vector<bool> local_edge(graph.edges.size(), false);
    bool any = false;
    for (size_t e = 0; e < graph.edges.size(); ++e) {
      local_edge[e] = in_window[indexed.a[e]] && in_window[indexed.b[e]];
      any = any || local_edge[e];
    }
    if (!any) continue;
    const RotationGraph local = Subgraph(graph, local_edge, nullptr);
    const RotationAveragingResult local_result = AverageRotations(local, local_options);
    // Gauge G of this window in the stitched frame: R_stitched = R_local G.
    Eigen::Quaterniond G = Eigen::Quaterniond::Identity();
    bool aligned = false;
    for (size_t k = 0; k < local.node_ids.size() && !aligned; ++k) {
      const int p = index.at(local.node_ids[k]);
      if (local_result.estimated[k] && known[p]) {
        G = local_result.rotations[k].conjugate() * stitched[p];
        aligned = true;
      }
    }
    if (!aligned) {  // attach through the heaviest edge from a stitched node into the window
      const auto local_index = NodeIndex(local);
      double best = -1.0;
      for (size_t e = 0; e < graph.edges.size(); ++e) {
        int from = indexed.a[e];
        int to = indexed.b[e];
        Eigen::Quaterniond R_from_to = graph.edges[e].R_ij;
        if (!known[from]) {
          std::swap(from, to);
          R_from_to = R_from_to.conjugate();
        }
        if (!known[from] || known[to] || !in_window[to]) continue;
        const auto it = local_index.find(graph.node_ids[to]);
        if (it == local_index.end() || !local_result.estimated[it->second]) continue;
        if (graph.edges[e].weight <= best) continue;
        best = graph.edges[e].weight;
        G = local_result.rotations[it->second].conjugate() * R_from_to * stitched[from];
      }
    }
    for (size_t k = 0; k < local.node_ids.size(); ++k) {
      const int p = index.at(local.node_ids[k]);
      if (!local_result.estimated[k] || known[p]) continue;
      stitched[p] = (local_result.rotations[k] * G).normalized();
      known[p] = true;
    }
  }
  const double window_seconds = timer.ElapsedSeconds();
  RotationAveragingResult result = AverageRotationsFrom(graph, stitched, known, options);
  result.timings.windows = window_seconds;
  result.timings.total += window_seconds;
  return result;
}

namespace {

// Solves the chordal normal equations (lower triangle in `triplets`, 3m x 3m) by CHOLMOD and
// projects each unknown's 3 x 3 block onto the nearest rotation.
void SolveChordalSystem(const std::vector<Eigen::Triplet<double, int>>& triplets,
                        const Eigen::MatrixXd& rhs, int m, const std::vector<int>& unknown,
                        std::vector<Eigen::Quaterniond>* rotations) {
  SparseMatrix H(3 * m, 3 * m);
  H.setFromTriplets(triplets.begin(), triplets.end());
  H.makeCompressed();
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> solver;
  solver.compute(H);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("chordal averaging: CHOLMOD factorisation failed");
  }
  const Eigen::MatrixXd X = solver.solve(rhs);
  for (size_t k = 0; k < unknown.size(); ++k) {
    if (unknown[k] < 0) continue;
    const Eigen::Matrix3d M = X.block<3, 3>(3 * unknown[k], 0);
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
    (*rotations)[k] = Eigen::Quaterniond(svd.matrixU() * D * svd.matrixV().transpose());
    (*rotations)[k].normalize();
  }
}

}  // namespace

ChordalAveragingResult AverageRotationsChordal(const RotationGraph& graph, bool refine,
                                               int max_refine_iterations,
                                               double refine_step_tolerance_deg) {
  Timer timer;
  ChordalAveragingResult result;
  const size_t n = graph.node_ids.size();
  const IndexedEdges indexed = IndexEdges(graph);
  const std::vector<int> labels = ConnectedComponents(graph);
  const std::vector<int> degree = NodeDegrees(graph);
  result.estimated.assign(n, false);
  result.rotations.assign(n, Eigen::Quaterniond::Identity());
  int pinned = -1;
  for (size_t k = 0; k < n; ++k) {
    result.estimated[k] = labels[k] == 0 && degree[k] > 0;
    if (result.estimated[k] && (pinned < 0 || degree[k] > degree[pinned])) pinned = int(k);
  }
  if (pinned < 0) return result;
  std::vector<int> unknown(n, -1);
  int m = 0;
  for (size_t k = 0; k < n; ++k) {
    if (result.estimated[k] && int(k) != pinned) unknown[k] = m++;
  }
  // Column c of X: sum_e ||x_b - A x_a||^2 with A = R_ij: blocks H_aa += I, H_bb += I,
  // H_ba -= A (lower triangle stored); the pinned node (x = e_c) moves to the right-hand side.
  std::vector<Eigen::Triplet<double, int>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(3 * m, 3);
  auto add_block = [&](int row_unknown, int col_unknown, const Eigen::Matrix3d& block) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        const int row = 3 * row_unknown + r;
        const int col = 3 * col_unknown + c;
        if (row >= col && block(r, c) != 0.0) triplets.emplace_back(row, col, block(r, c));
      }
    }
  };
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    const int a = indexed.a[e];
    const int b = indexed.b[e];
    if (!result.estimated[a] || !result.estimated[b]) continue;
    const Eigen::Matrix3d A = graph.edges[e].R_ij.toRotationMatrix();
    const int ua = unknown[a];
    const int ub = unknown[b];
    if (ua >= 0) add_block(ua, ua, Eigen::Matrix3d::Identity());
    if (ub >= 0) add_block(ub, ub, Eigen::Matrix3d::Identity());
    if (ua >= 0 && ub >= 0) {
      if (ub > ua) {
        add_block(ub, ua, -A);
      } else {
        add_block(ua, ub, -A.transpose());
      }
    } else if (ua < 0) {  // x_a = I: ||x_b - A||^2, rhs_b += A
      rhs.block<3, 3>(3 * ub, 0) += A;
    } else {  // x_b = I: ||I - A x_a||^2, rhs_a += A^T
      rhs.block<3, 3>(3 * ua, 0) += A.transpose();
    }
  }
  if (m > 0) SolveChordalSystem(triplets, rhs, m, unknown, &result.rotations);
  if (refine) {
    std::vector<size_t> edges;
    for (size_t e = 0; e < graph.edges.size(); ++e) {
      if (result.estimated[indexed.a[e]] && result.estimated[indexed.b[e]]) edges.push_back(e);
    }
    const std::vector<double> unit_weights(graph.edges.size(), 1.0);
    TangentIrls chordal(graph, indexed.a, indexed.b, edges, result.estimated, unit_weights,
                        PcgOptions(RotationAveragingOptions()));
    result.refine_iterations =
        chordal.Run(ChordalWeight, max_refine_iterations, refine_step_tolerance_deg * kDegToRad,
                    &result.rotations);
  }
  result.seconds = timer.ElapsedSeconds();
  return result;
}

}  // namespace ramap
