#include "ramap/averaging/translation_averaging.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "ramap/averaging/block_normal_equations.h"
#include "ramap/averaging/preconditioned_cg.h"
#include "ramap/averaging/shifted_cholesky.h"
#include "ramap/geometry/rotation.h"
#include "ramap/geometry/triangulation.h"
#include "ramap/util/disjoint_sets.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/run_observer.h"
#include "ramap/util/statistics.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

uint64_t PairKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// The point of a track as predicted from the pair (from, to): X = c_from + M (c_to - c_from).
struct PointPrediction {
  uint32_t from = 0;
  uint32_t to = 0;
  Eigen::Vector3d baseline = Eigen::Vector3d::Zero();  // unit direction of c_to - c_from
  Eigen::Vector3d ray_from = Eigen::Vector3d::Zero();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();  // set by WithMatrix, for the chosen ones only
  double depth_ratio = 0.0;                     // |X - c_from| / |c_to - c_from|
  double ray_angle = 0.0;                       // angle between the two rays, radians
};

class DirectionTable {
 public:
  explicit DirectionTable(const std::vector<PairDirection>& directions) {
    for (const PairDirection& pair : directions) {
      if (pair.image_id1 == pair.image_id2 || !pair.direction.allFinite()) continue;
      const Eigen::Vector3d d = pair.direction.normalized();
      table_[PairKey(pair.image_id1, pair.image_id2)] = pair.image_id1 < pair.image_id2 ? d : -d;
    }
  }
  // Unit direction of c_to - c_from, if known.
  std::optional<Eigen::Vector3d> Get(uint32_t from, uint32_t to) const {
    const auto it = table_.find(PairKey(from, to));
    if (it == table_.end()) return std::nullopt;
    return from < to ? it->second : Eigen::Vector3d(-it->second);
  }

 private:
  std::unordered_map<uint64_t, Eigen::Vector3d> table_;
};

// Law-of-sines triangle (c_from, c_to, X) with unit baseline; empty when ill-conditioned or when X
// would lie behind a camera.
std::optional<PointPrediction> PredictPoint(uint32_t from, uint32_t to,
                                            const Eigen::Vector3d& ray_from,
                                            const Eigen::Vector3d& ray_to,
                                            const DirectionTable& directions,
                                            double min_ray_angle) {
  const std::optional<Eigen::Vector3d> baseline = directions.Get(from, to);
  if (!baseline) return std::nullopt;
  const double ray_angle = std::acos(std::clamp(ray_from.dot(ray_to), -1.0, 1.0));
  if (ray_angle < min_ray_angle) return std::nullopt;
  // depth_from * ray_from - depth_to * ray_to = baseline (unit length).
  const std::optional<Eigen::Vector2d> depths = TwoRayDepths(ray_from, ray_to, *baseline);
  if (!depths || !((*depths)(0) > 0 && (*depths)(1) > 0)) return std::nullopt;
  PointPrediction prediction;
  prediction.from = from;
  prediction.to = to;
  prediction.baseline = *baseline;
  prediction.ray_from = ray_from;
  prediction.depth_ratio = (*depths)(0);
  prediction.ray_angle = ray_angle;
  return prediction;
}

// The prediction with its matrix M, which turns the baseline into the point's offset from c_from
// (a track compares n^2 predictions and keeps about n, so only those build it).
PointPrediction WithMatrix(PointPrediction prediction) {
  prediction.M = prediction.depth_ratio *
                 Eigen::Quaterniond::FromTwoVectors(prediction.baseline, prediction.ray_from)
                     .toRotationMatrix();
  return prediction;
}

// One 3-row block: prediction_a(c) - prediction_b(c) = 0, scaled to baseline units.
struct Constraint {
  PointPrediction a;
  PointPrediction b;
  double weight = 1.0;
};

// What a track's observation needs of its camera: the rotation and the keypoints' bearings.
struct CameraRays {
  const Eigen::Quaterniond* rotation = nullptr;
  const std::vector<Eigen::Vector3d>* bearings = nullptr;
};

// The cameras of `rotations` that have bearings, looked up once per camera rather than twice per
// observation.
std::unordered_map<uint32_t, CameraRays> RotatedCameraRays(
    const std::map<uint32_t, Eigen::Quaterniond>& rotations, const KeypointBearings& bearings) {
  std::unordered_map<uint32_t, CameraRays> cameras;
  cameras.reserve(rotations.size());
  for (const auto& [image_id, rotation] : rotations) {
    const auto found = bearings.find(image_id);
    if (found != bearings.end()) cameras[image_id] = {&rotation, &found->second};
  }
  return cameras;
}

// The cameras of a track that constraints will use, with their world-frame rays: of a long track,
// those with the fewest constraints so far, so that every camera gets its share and none is left
// out by the cap.
void SelectTrackRays(const Track& track, const std::unordered_map<uint32_t, CameraRays>& cameras,
                     const TranslationAveragingOptions& options,
                     std::unordered_map<uint32_t, int>* usage, std::vector<uint32_t>* ids,
                     std::vector<Eigen::Vector3d>* rays) {
  struct Usable {
    int uses;  // the camera's constraints so far
    const TrackElement* element;
    const CameraRays* camera;
  };
  std::vector<Usable> usable;
  usable.reserve(track.size());
  for (const TrackElement& element : track) {
    const auto camera = cameras.find(element.image_id);
    if (camera == cameras.end() || element.point2D_idx >= camera->second.bearings->size()) continue;
    usable.push_back({(*usage)[element.image_id], &element, &camera->second});
  }
  std::stable_sort(usable.begin(), usable.end(),
                   [](const Usable& x, const Usable& y) { return x.uses < y.uses; });
  // The bearings are read only for the cameras taken: they are scattered over every image's
  // keypoints, and a long track's others would each cost a cache miss.
  for (const Usable& observation : usable) {
    const uint32_t image_id = observation.element->image_id;
    if (std::find(ids->begin(), ids->end(), image_id) != ids->end()) continue;
    const Eigen::Vector3d& bearing =
        (*observation.camera->bearings)[observation.element->point2D_idx];
    if (!bearing.allFinite()) continue;
    ids->push_back(image_id);
    rays->push_back((observation.camera->rotation->conjugate() * bearing).normalized());
    if (static_cast<int>(ids->size()) >= options.max_observations_per_track) break;
  }
}

// The constraints of one track: its best-conditioned pair (widest ray angle) predicts the point,
// and every other camera predicts it again from its own best pair. Returns how many were added.
int AddTrackConstraints(const std::vector<uint32_t>& ids, const std::vector<Eigen::Vector3d>& rays,
                        const DirectionTable& directions, double min_angle,
                        std::unordered_map<uint32_t, int>* usage,
                        std::vector<Constraint>* constraints) {
  // Every ordered pair's prediction, once: the reference and each camera's best pair are chosen
  // among the same ones.
  const size_t n = ids.size();
  std::vector<std::optional<PointPrediction>> predictions(n * n);
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      if (a != b)
        predictions[a * n + b] =
            PredictPoint(ids[a], ids[b], rays[a], rays[b], directions, min_angle);
    }
  }
  const auto wider = [](const std::optional<PointPrediction>& x,
                        const std::optional<PointPrediction>& than) {
    return x && (!than || x->ray_angle > than->ray_angle);
  };
  std::optional<PointPrediction> reference;
  size_t ref_a = 0;
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      if (wider(predictions[a * n + b], reference)) reference = predictions[a * n + b], ref_a = a;
    }
  }
  if (!reference) return 0;
  const PointPrediction reference_point = WithMatrix(*reference);
  int added = 0;
  for (size_t k = 0; k < n; ++k) {
    if (k == ref_a) continue;
    // Camera k predicts X from its best-conditioned pair with any other camera of the track
    // (a sequence frame often has no verified pair with the reference cameras themselves).
    std::optional<PointPrediction> best;
    for (size_t partner = 0; partner < n; ++partner) {
      if (wider(predictions[k * n + partner], best)) best = predictions[k * n + partner];
    }
    if (!best) continue;
    Constraint constraint;
    constraint.a = reference_point;
    constraint.b = WithMatrix(*best);
    // Residuals are point displacements; dividing by the depth ratio expresses them in baselines,
    // so that far points do not dominate.
    constraint.weight = 1.0 / std::max({1.0, reference->depth_ratio, best->depth_ratio});
    constraints->push_back(constraint);
    for (const uint32_t id : {ids[k], best->to}) ++(*usage)[id];
    ++added;
  }
  return added;
}

std::vector<Constraint> BuildConstraints(const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                         const DirectionTable& directions,
                                         const std::vector<Track>& tracks,
                                         const KeypointBearings& bearings,
                                         const TranslationAveragingOptions& options,
                                         int* num_tracks_used) {
  const std::unordered_map<uint32_t, CameraRays> cameras = RotatedCameraRays(rotations, bearings);
  const double min_angle = options.min_triangulation_angle_deg * kDegToRad;
  // Longer tracks first (counting every observation, usable or not): they carry more constraints
  // per point.
  std::vector<size_t> order(tracks.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return tracks[x].size() > tracks[y].size(); });
  const bool quota = options.min_tracks_per_image > 0;
  std::vector<Constraint> constraints;
  std::unordered_map<uint32_t, int> usage;      // constraints per camera so far
  std::unordered_map<uint32_t, int> tracks_of;  // tracks per camera so far
  // Past max_num_tracks, a track is still used while one of its cameras has fewer than
  // min_tracks_per_image tracks: a global cap alone gives the longest tracks, which cluster (slow
  // stretches, revisits) and leave the rest of a long drive without any.
  const auto wanted = [&](const Track& track) {
    if (*num_tracks_used < options.max_num_tracks) return true;
    return std::any_of(track.begin(), track.end(), [&](const TrackElement& element) {
      if (!cameras.count(element.image_id)) return false;
      const auto found = tracks_of.find(element.image_id);
      return found == tracks_of.end() || found->second < options.min_tracks_per_image;
    });
  };
  *num_tracks_used = 0;
  int num_tried = 0;
  for (const size_t track_index : order) {
    // Without a quota, the first max_num_tracks tracks are tried, used or not.
    if (!quota && num_tried++ >= options.max_num_tracks) break;
    if (quota && !wanted(tracks[track_index])) continue;
    std::vector<uint32_t> ids;
    std::vector<Eigen::Vector3d> rays;
    SelectTrackRays(tracks[track_index], cameras, options, &usage, &ids, &rays);
    if (ids.size() < 2) continue;
    if (AddTrackConstraints(ids, rays, directions, min_angle, &usage, &constraints) == 0) continue;
    ++*num_tracks_used;
    for (const uint32_t id : ids) ++tracks_of[id];
  }
  return constraints;
}

// The stacked system B v, v = (centres, pair scales, prior constants). Blocks: tracks, pairs,
// priors. A pair scale is bounded below by `scale_bound`; a prior constant is held at 1 (it
// multiplies the prior's position, moving it to the right-hand side).
struct StackedSystem {
  Eigen::SparseMatrix<double> B;
  // B by rows, for products over row ranges on several threads (ResidualsOf) and for the normal
  // equations' blocks (BlockNormalEquations).
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows;
  int num_threads = 1;
  int num_position_cols = 0;
  int num_pair_scales = 0;
  int num_prior_columns = 0;
  double scale_bound = 1.0;
  double prior_min_residual = 1.0;  // IRLS residual floor of prior blocks (Huber at one sigma)

  int num_extra_cols() const { return num_pair_scales + num_prior_columns; }
};

// B x, its rows in fixed shares on system.num_threads threads. Each entry sums its row in column
// order, as the product by the column-major B does: the same numbers on any number of threads.
Eigen::VectorXd ResidualsOf(const StackedSystem& system, const Eigen::VectorXd& x) {
  const size_t num_rows = static_cast<size_t>(system.rows.rows());
  // A share smaller than this gains less than its thread costs.
  constexpr size_t kMinRowsPerShare = 6000;
  const size_t num_shares = NumShares(num_rows, system.num_threads, kMinRowsPerShare);
  if (num_shares == 1) return system.rows * x;
  Eigen::VectorXd residuals(num_rows);
  ForEachShare(num_rows, num_shares, [&](size_t, size_t begin, size_t end) {
    const auto length = static_cast<Eigen::Index>(end - begin);
    residuals.segment(static_cast<Eigen::Index>(begin), length) =
        system.rows.middleRows(static_cast<Eigen::Index>(begin), length) * x;
  });
  return residuals;
}

Eigen::VectorXd SoftThreshold(const Eigen::VectorXd& v, double kappa) {
  return (v.array() - kappa).max(0.0) - (-v.array() - kappa).max(0.0);
}

Eigen::VectorXd ProjectScales(Eigen::VectorXd v, const StackedSystem& system) {
  v.segment(system.num_position_cols, system.num_pair_scales) =
      v.segment(system.num_position_cols, system.num_pair_scales).cwiseMax(system.scale_bound);
  v.tail(system.num_prior_columns).setOnes();
  return v;
}

// min ||B v||_1 over v = (positions, scales >= bound, prior constants = 1) by ADMM, from `x`
// (feasible).
Eigen::VectorXd SolveByAdmm(const StackedSystem& system, Eigen::VectorXd x,
                            const TranslationAveragingOptions& options, int* iterations) {
  const Eigen::SparseMatrix<double>& B = system.B;
  const int num_rows = static_cast<int>(B.rows());
  const int num_cols = static_cast<int>(B.cols());
  Eigen::SparseMatrix<double> ridge(num_cols, num_cols);
  ridge.setIdentity();
  const Eigen::SparseMatrix<double> normal = B.transpose() * B;
  // ADMM on min ||z||_1 + [scales >= 1](x) s.t. z = B y, x = y (scaled form; Boyd et al. 2011).
  // The y-update's matrix B^T B + I does not depend on rho, so it is factored once.
  const Eigen::SparseMatrix<double> admm_matrix = normal + ridge;
  ShiftedCholesky admm_step(admm_matrix);
  admm_step.Factorize(admm_matrix);
  Eigen::VectorXd y = x;
  Eigen::VectorXd z = B * y;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(num_rows);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(num_cols);
  double rho = options.admm_rho;
  const double tolerance_primal =
      options.admm_tolerance * std::sqrt(static_cast<double>(num_rows + num_cols));
  const double tolerance_dual = options.admm_tolerance * std::sqrt(static_cast<double>(num_cols));
  constexpr int kCostCheckInterval = 50;
  double previous_cost = std::numeric_limits<double>::infinity();
  int iteration = 0;
  for (; iteration < options.max_admm_iterations; ++iteration) {
    CheckForStop();
    y = admm_step.Solve(B.transpose() * (z - u) + (x - w));
    const Eigen::VectorXd By = B * y;
    const Eigen::VectorXd By_relaxed =
        options.admm_relaxation * By + (1.0 - options.admm_relaxation) * z;
    const Eigen::VectorXd z_previous = z;
    const Eigen::VectorXd x_previous = x;
    z = SoftThreshold(By_relaxed + u, 1.0 / rho);
    x = ProjectScales(y + w, system);
    u += By_relaxed - z;
    w += y - x;
    const double primal = std::sqrt((By - z).squaredNorm() + (y - x).squaredNorm());
    const double dual = rho * (B.transpose() * (z - z_previous) + (x - x_previous)).norm();
    // Stopping rule of Boyd et al. 2011, sec. 3.3.1: absolute plus relative tolerances.
    const double relative = options.admm_relative_tolerance;
    if (primal < tolerance_primal + relative * std::max(By.norm(), z.norm()) &&
        dual < tolerance_dual + relative * rho * (B.transpose() * u + w).norm()) {
      ++iteration;
      break;
    }
    // Residual balancing (Boyd et al. 2011, sec. 3.4.1): the y-update does not depend on rho, so
    // changing it costs nothing but rescaling the scaled duals.
    if (options.admm_adaptive_rho) {
      if (primal > 10.0 * dual) {
        rho *= 2.0, u /= 2.0, w /= 2.0;
      } else if (dual > 10.0 * primal) {
        rho /= 2.0, u *= 2.0, w *= 2.0;
      }
    }
    // ADMM's residuals shrink slowly once the L1 cost has settled (its tail is long): stop when the
    // cost changed by less than admm_cost_tolerance over the last check window.
    if (iteration % kCostCheckInterval == kCostCheckInterval - 1) {
      const double cost = (B * x).lpNorm<1>();
      if (std::abs(previous_cost - cost) <= options.admm_cost_tolerance * cost) {
        ++iteration;
        break;
      }
      previous_cost = cost;
    }
  }

  *iterations = iteration;
  return x;
}

// The IRLS layout of a stacked system: its 3-row blocks (tracks, then one per pair scale, then one
// per prior) and each pair scale's column within its pair row.
struct IrlsLayout {
  int num_blocks = 0;
  int first_pair_block = 0;
  int first_prior_block = 0;
  std::vector<Eigen::Vector3d> scale_columns;  // the pair row of scale k is w (c_j - c_i - s d)
};

IrlsLayout MakeIrlsLayout(const StackedSystem& system) {
  IrlsLayout layout;
  layout.num_blocks = static_cast<int>(system.B.rows()) / 3;
  layout.first_pair_block = layout.num_blocks - system.num_extra_cols();
  layout.first_prior_block = layout.first_pair_block + system.num_pair_scales;
  layout.scale_columns.assign(system.num_pair_scales, Eigen::Vector3d::Zero());
  for (int k = 0; k < system.num_pair_scales; ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(system.B, system.num_position_cols + k); it;
         ++it) {
      layout.scale_columns[k](it.row() - 3 * (layout.first_pair_block + k)) = it.value();
    }
  }
  return layout;
}

// The IRLS weights 1 / max(|r_b|, floor_b) of the residuals B x, and the smoothed objective the
// weighted squares majorise: |r| above the floor, (r^2 / floor + floor) / 2 below it, so at least
// floor / 2 per block (`least_cost` receives that least value).
double IrlsWeights(const StackedSystem& system, const IrlsLayout& layout,
                   const Eigen::VectorXd& residuals, const TranslationAveragingOptions& options,
                   Eigen::VectorXd* block_weights, double* least_cost) {
  block_weights->resize(layout.num_blocks);
  double cost = 0;
  *least_cost = 0;
  for (int b = 0; b < layout.num_blocks; ++b) {
    const double floor =
        b >= layout.first_prior_block ? system.prior_min_residual : options.irls_min_residual;
    const double norm = residuals.segment<3>(3 * b).norm();
    (*block_weights)(b) = 1.0 / std::max(norm, floor);
    cost += norm > floor ? norm : 0.5 * (norm * norm / floor + floor);
    *least_cost += 0.5 * floor;
  }
  return cost;
}

// The smoothed objective of IrlsWeights for the residuals B x.
double IrlsObjective(const StackedSystem& system, const IrlsLayout& layout,
                     const Eigen::VectorXd& residuals, const TranslationAveragingOptions& options) {
  Eigen::VectorXd weights;
  double least_cost = 0;
  return IrlsWeights(system, layout, residuals, options, &weights, &least_cost);
}

// Active set of the pair scales after a step to `next`: a free scale below the bound is held; a
// held scale is released when its pair row alone (the only row it appears in) would put it above
// the bound. Without priors every row is homogeneous but for the held scales, so at least one
// must stay held: the one its pair would lengthen least. `next_residuals` (B next) are brought up
// to date when a scale moves to its bound. Returns how many scales changed set.
int UpdateHeldScales(const StackedSystem& system, const IrlsLayout& layout, Eigen::VectorXd* next,
                     Eigen::VectorXd* next_residuals, std::vector<bool>* held) {
  bool clipped = false;
  const std::vector<bool> before = *held;
  int tightest = -1;
  double tightest_preferred = std::numeric_limits<double>::infinity();
  for (int k = 0; k < system.num_pair_scales; ++k) {
    double& scale = (*next)(system.num_position_cols + k);
    if ((*held)[k]) {
      const Eigen::Vector3d& column = layout.scale_columns[k];
      const double preferred =
          scale - column.dot(next_residuals->segment<3>(3 * (layout.first_pair_block + k))) /
                      column.squaredNorm();
      if (preferred < tightest_preferred) tightest_preferred = preferred, tightest = k;
      if (preferred > system.scale_bound) (*held)[k] = false;
    } else if (scale < system.scale_bound) {
      scale = system.scale_bound;
      (*held)[k] = true;
      clipped = true;
    }
  }
  if (clipped) *next_residuals = ResidualsOf(system, *next);
  if (system.num_prior_columns == 0 && std::find(held->begin(), held->end(), true) == held->end() &&
      tightest >= 0) {
    (*held)[tightest] = true;
  }
  int moved = 0;
  for (size_t k = 0; k < held->size(); ++k) moved += (*held)[k] != before[k];
  return moved;
}

// The stacked system's weighted least squares over the camera positions alone: the pair scales
// and prior constants eliminated (block_normal_equations.h), the pattern analysed once for the
// least-squares start and every IRLS step.
class PositionSolver {
 public:
  PositionSolver(const StackedSystem& system, const TranslationAveragingOptions& options)
      : equations_(system.rows, ExtraColumns(system)),
        num_threads_(system.num_threads),
        pcg_{options.max_pcg_iterations, options.pcg_tolerance},
        factorization_(equations_.pattern()) {}

  // v = (positions, scales, constants) minimising sum_b w_b |B_b v|^2 with the held scales at
  // their values and the free ones at their rows' minimisers.
  Eigen::VectorXd Solve(const Eigen::VectorXd& block_weights, const std::vector<bool>& held,
                        const std::vector<double>& held_values) {
    equations_.Assemble(block_weights, held, held_values, &normal_, &rhs_, num_threads_);
    if (!SolveWithLastFactor()) {
      shift_ = factorization_.Factorize(normal_);
      last_solution_ = factorization_.Solve(rhs_);
      ++num_factorizations_;
    }
    return equations_.Expand(last_solution_, held, held_values);
  }

  int num_factorizations() const { return num_factorizations_; }

 private:
  static std::vector<int> ExtraColumns(const StackedSystem& system) {
    std::vector<int> columns(system.num_extra_cols());
    std::iota(columns.begin(), columns.end(), system.num_position_cols);
    return columns;
  }

  // Conjugate gradients on the new equations, preconditioned by the last factorisation and started
  // from the last solution (TranslationAveragingOptions::max_pcg_iterations); last_solution_
  // becomes the result. False, last_solution_ unchanged, when there is no factor yet or the
  // residual does not reach the tolerance in time.
  bool SolveWithLastFactor() {
    if (num_factorizations_ == 0) return false;
    const auto normal = normal_.selfadjointView<Eigen::Lower>();
    // The same shift as the last factorisation's (ShiftedCholesky::Factorize), so that a step
    // solves the system a refactorisation would have.
    const auto apply = [&](const Eigen::MatrixXd& v) -> Eigen::MatrixXd {
      return normal * v + shift_ * v;
    };
    const auto precondition = [&](const Eigen::MatrixXd& r) -> Eigen::MatrixXd {
      return factorization_.Solve(r.col(0));
    };
    Eigen::MatrixXd solution = last_solution_;
    if (!SolveByPreconditionedCg(apply, precondition, rhs_, pcg_, &solution)) return false;
    last_solution_ = solution.col(0);
    return true;
  }

  BlockNormalEquations equations_;
  int num_threads_ = 1;
  Eigen::SparseMatrix<double> normal_;
  Eigen::VectorXd rhs_;
  Eigen::VectorXd last_solution_;  // of the reduced equations
  double shift_ = 0;               // of the last factorisation
  int num_factorizations_ = 0;
  PreconditionedCgOptions pcg_;
  ShiftedCholesky factorization_;  // after equations_, whose pattern it analyses
};

// The same problem by iteratively reweighted least squares: each 3-row block (a track constraint
// or a pair row) is weighted by 1 / max(|r|, irls_min_residual), which makes the weighted squares
// an approximation of the sum of block norms (the L1 objective of Ozyesil & Singer's LUD), and each
// step is one sparse solve, so that scale travels the length of a long sequence in one step rather
// than over thousands of ADMM iterations (block_normal_equations.h keeps each step to a reweighting
// and a solve of the camera system: PositionSolver). Scales at their bound are held
// there (their columns move to the right-hand side), the others are eliminated at their rows'
// minimiser; a held scale is released when its pair row alone would want it above the bound.
// Prior constants are always held at 1; prior blocks are weighted by 1 / max(|r|,
// prior_min_residual), a Huber loss on residuals in standard deviations. Stops when the positions
// move by less than irls_tolerance, or when a step that left the held scales nearly as they were
// lowered the objective by less than irls_cost_tolerance of its excess over its least value (on
// exact data that excess vanishes and the steps go on to the exact solution); the best iterate is
// returned.
Eigen::VectorXd SolveByIrls(const StackedSystem& system, Eigen::VectorXd x,
                            const TranslationAveragingOptions& options, PositionSolver* solver,
                            int* iterations) {
  const int num_position_cols = system.num_position_cols;
  const int num_scales = system.num_extra_cols();
  const IrlsLayout layout = MakeIrlsLayout(system);
  std::vector<bool> held(num_scales);
  for (int k = 0; k < num_scales; ++k) {
    held[k] = k >= system.num_pair_scales || x(num_position_cols + k) <= system.scale_bound;
  }
  std::vector<double> held_values(num_scales, system.scale_bound);
  for (int k = system.num_pair_scales; k < num_scales; ++k) held_values[k] = 1.0;
  Eigen::VectorXd block_weights;
  Eigen::VectorXd residuals = ResidualsOf(system, x);  // kept with x: each product is a pass over B
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_x = x;
  // Objectives compare across a step only while the active set stays nearly the same: on the
  // first steps many scales leave their bound and the objective may barely move before it falls.
  constexpr double kSettledShareOfScales = 0.01;
  int num_moved = num_scales;
  int iteration = 0;
  for (; iteration < options.max_irls_iterations; ++iteration) {
    CheckForStop();
    double least_cost = 0;
    const double cost =
        IrlsWeights(system, layout, residuals, options, &block_weights, &least_cost);
    const bool settled = num_moved <= kSettledShareOfScales * num_scales &&
                         best_cost - cost < options.irls_cost_tolerance * (best_cost - least_cost);
    if (cost < best_cost) best_cost = cost, best_x = x;
    if (settled) break;
    Eigen::VectorXd next = solver->Solve(block_weights, held, held_values);
    Eigen::VectorXd next_residuals = ResidualsOf(system, next);
    if (options.irls_extrapolation > 1) {
      Eigen::VectorXd extrapolated =
          ProjectScales(x + options.irls_extrapolation * (next - x), system);
      Eigen::VectorXd extrapolated_residuals = ResidualsOf(system, extrapolated);
      if (IrlsObjective(system, layout, extrapolated_residuals, options) <
          IrlsObjective(system, layout, next_residuals, options)) {
        next = std::move(extrapolated);
        next_residuals = std::move(extrapolated_residuals);
      }
    }
    num_moved = UpdateHeldScales(system, layout, &next, &next_residuals, &held);
    const double change = (next.head(num_position_cols) - x.head(num_position_cols)).norm() /
                          std::max(1e-12, next.head(num_position_cols).norm());
    x = std::move(next);
    residuals = std::move(next_residuals);
    if (change < options.irls_tolerance) {
      ++iteration;
      break;
    }
  }
  *iterations = iteration;
  // The last step's result unless an earlier iterate had the lower objective.
  double least_cost = 0;
  const double cost = IrlsWeights(system, layout, residuals, options, &block_weights, &least_cost);
  return cost <= best_cost ? x : best_x;
}

}  // namespace

void TranslationAveragingOptions::Check() const {
  CheckOptionValues(TranslationAveragingOptionTable(), *this);
  // The settings no command line option reaches.
  const std::string s = "TranslationAveragingOptions::";
  CheckOption(max_observations_per_track >= 2, s + "max_observations_per_track", ">= 2",
              max_observations_per_track);
  CheckOption(prior_weight > 0, s + "prior_weight", "> 0", prior_weight);
  CheckOption(prior_huber_sigmas > 0, s + "prior_huber_sigmas", "> 0", prior_huber_sigmas);
  CheckOption(admm_relaxation > 0 && admm_relaxation < 2, s + "admm_relaxation", "in (0, 2)",
              admm_relaxation);
  CheckOption(irls_tolerance > 0, s + "irls_tolerance", "> 0", irls_tolerance);
  CheckOption(num_threads >= 1, s + "num_threads", ">= 1", num_threads);
  CheckOption(pcg_tolerance > 0 && pcg_tolerance < 1, s + "pcg_tolerance", "in (0, 1)",
              pcg_tolerance);
  CheckOption(irls_min_residual > 0, s + "irls_min_residual", "> 0", irls_min_residual);
  CheckOption(admm_tolerance > 0, s + "admm_tolerance", "> 0", admm_tolerance);
  CheckOption(admm_cost_tolerance >= 0, s + "admm_cost_tolerance", ">= 0", admm_cost_tolerance);
  CheckOption(admm_relative_tolerance >= 0, s + "admm_relative_tolerance", ">= 0",
              admm_relative_tolerance);
}

namespace {

// Pair rows: c_j - c_i = s_ij d_ij with a scale s_ij >= 1 per pair (Ozyesil & Singer, "Robust
// camera location estimation by convex programming", CVPR 2015). The bound fixes the scale and
// makes the problem convex; without it the homogeneous track system admits collapsed solutions
// (normalised on a sphere instead, the L1 solution of a drive put all the scale on its first
// frames and the others on one point).
struct PairRow {
  uint32_t i = 0, j = 0;
  Eigen::Vector3d direction;
};

// The pair directions between two rotated images, unit length.
std::vector<PairRow> UsablePairRows(const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                    const std::vector<PairDirection>& pair_directions) {
  std::vector<PairRow> pairs;
  for (const PairDirection& pair : pair_directions) {
    if (pair.image_id1 == pair.image_id2 || !pair.direction.allFinite() ||
        pair.direction.norm() == 0 || !rotations.count(pair.image_id1) ||
        !rotations.count(pair.image_id2)) {
      continue;
    }
    pairs.push_back({pair.image_id1, pair.image_id2, pair.direction.normalized()});
  }
  return pairs;
}

// The largest set of images that the constraints and pairs connect, increasing (the first is the
// gauge camera; of two as large, the one with the smaller first image); the other rotated images
// go to `unconstrained`.
std::vector<uint32_t> LargestConnectedImages(
    const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<Constraint>& constraints, const std::vector<PairRow>& pairs,
    std::vector<uint32_t>* unconstrained) {
  // Images by their position in `rotations`, in increasing id order.
  std::vector<uint32_t> ids;
  std::unordered_map<uint32_t, uint32_t> index;
  for (const auto& [image_id, rotation] : rotations) {
    (void)rotation;
    index[image_id] = static_cast<uint32_t>(ids.size());
    ids.push_back(image_id);
  }
  DisjointSets components(ids.size());
  std::vector<bool> constrained(ids.size(), false);
  const auto link = [&](uint32_t image_id1, uint32_t image_id2) {
    const uint32_t a = index.at(image_id1), b = index.at(image_id2);
    components.Union(a, b);
    constrained[a] = constrained[b] = true;
  };
  for (const Constraint& c : constraints) {
    for (const uint32_t id : {c.a.to, c.b.from, c.b.to}) link(c.a.from, id);
  }
  for (const PairRow& pair : pairs) link(pair.i, pair.j);
  const std::vector<uint32_t> roots = components.Roots();
  std::vector<int> component_size(ids.size(), 0);
  for (size_t k = 0; k < ids.size(); ++k) component_size[roots[k]] += constrained[k];
  const uint32_t largest = static_cast<uint32_t>(
      std::max_element(component_size.begin(), component_size.end()) - component_size.begin());
  std::vector<uint32_t> solved;
  for (size_t k = 0; k < ids.size(); ++k) {
    if (constrained[k] && roots[k] == largest) {
      solved.push_back(ids[k]);
    } else {
      unconstrained->push_back(ids[k]);
    }
  }
  return solved;
}

// The usable priors of the solved images.
std::vector<PosePriorInModel> PriorsOfSolvedImages(const std::vector<uint32_t>& solved,
                                                   const std::vector<PosePriorInModel>& priors) {
  const std::set<uint32_t> solved_set(solved.begin(), solved.end());
  std::vector<PosePriorInModel> used;
  for (const PosePriorInModel& prior : priors) {
    if (solved_set.count(prior.image_id) && prior.center.allFinite() &&
        prior.sqrt_information.allFinite()) {
      used.push_back(prior);
    }
  }
  return used;
}

// B v = 0 with v = (centres of all cameras but the gauge camera, fixed at the origin; one scale
// per pair; with priors, every centre and one constant per prior). Track rows first, then pair
// rows, then prior rows. `column` maps an image to its camera index (the gauge camera: -1).
StackedSystem AssembleSystem(const std::vector<Constraint>& constraints,
                             const std::vector<PairRow>& pairs,
                             const std::vector<PosePriorInModel>& used_priors,
                             const std::map<uint32_t, int>& column, int num_cameras,
                             const TranslationAveragingOptions& options) {
  const int num_position_cols = 3 * num_cameras;
  const int num_cols = num_position_cols + static_cast<int>(pairs.size() + used_priors.size());
  const int num_rows = 3 * static_cast<int>(constraints.size() + pairs.size() + used_priors.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(constraints.size() * 36 + pairs.size() * 9);
  auto add_block = [&](int row, uint32_t image_id, const Eigen::Matrix3d& block) {
    const int cam = column.at(image_id);
    if (cam < 0) return;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        if (block(r, c) != 0.0) triplets.emplace_back(row + r, 3 * cam + c, block(r, c));
      }
    }
  };
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (size_t k = 0; k < constraints.size(); ++k) {
    const Constraint& c = constraints[k];
    const int row = 3 * static_cast<int>(k);
    // c_from + M (c_to - c_from) for the reference minus the same for the other camera.
    add_block(row, c.a.from, c.weight * (I - c.a.M));
    add_block(row, c.a.to, c.weight * c.a.M);
    add_block(row, c.b.from, -c.weight * (I - c.b.M));
    add_block(row, c.b.to, -c.weight * c.b.M);
  }
  const double w_pair = options.pair_constraint_weight;
  for (size_t k = 0; k < pairs.size(); ++k) {
    const int row = 3 * static_cast<int>(constraints.size() + k);
    add_block(row, pairs[k].j, w_pair * I);
    add_block(row, pairs[k].i, -w_pair * I);
    for (int r = 0; r < 3; ++r) {
      triplets.emplace_back(row + r, num_position_cols + static_cast<int>(k),
                            -w_pair * pairs[k].direction(r));
    }
  }
  // Prior rows: W (c - p) = W c - (W p) * 1, the constant column held at 1.
  for (size_t k = 0; k < used_priors.size(); ++k) {
    const int row = 3 * static_cast<int>(constraints.size() + pairs.size() + k);
    const Eigen::Matrix3d W = options.prior_weight * used_priors[k].sqrt_information;
    add_block(row, used_priors[k].image_id, W);
    const Eigen::Vector3d constant = -(W * used_priors[k].center);
    for (int r = 0; r < 3; ++r) {
      triplets.emplace_back(row + r, num_position_cols + static_cast<int>(pairs.size() + k),
                            constant(r));
    }
  }
  StackedSystem system;
  system.B.resize(num_rows, num_cols);
  system.B.setFromTriplets(triplets.begin(), triplets.end());
  system.rows = system.B;
  system.num_threads = options.num_threads;
  system.num_position_cols = num_position_cols;
  system.num_pair_scales = static_cast<int>(pairs.size());
  system.num_prior_columns = static_cast<int>(used_priors.size());
  // The bound s >= 1 only excludes the collapsed solutions; priors already do, and in their units
  // a baseline may be any length.
  system.scale_bound = used_priors.empty() ? 1.0 : 0.0;
  system.prior_min_residual = options.prior_huber_sigmas * options.prior_weight;
  return system;
}

// The centre of an image in solution `x` (the gauge camera at the origin).
Eigen::Vector3d CenterIn(const Eigen::VectorXd& x, const std::map<uint32_t, int>& column,
                         uint32_t image_id) {
  const int cam = column.at(image_id);
  return cam < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(x.segment<3>(3 * cam));
}

// Start: least squares with every scale at 1, min ||B_c c + B_s 1||^2, then each scale set to the
// projected baseline it implies (at least the bound).
Eigen::VectorXd LeastSquaresStart(const StackedSystem& system, const std::vector<PairRow>& pairs,
                                  const std::map<uint32_t, int>& column, PositionSolver* solver) {
  const int num_blocks = static_cast<int>(system.B.rows() / 3);
  const int num_extra = system.num_extra_cols();
  Eigen::VectorXd x =
      solver->Solve(Eigen::VectorXd::Ones(num_blocks), std::vector<bool>(num_extra, true),
                    std::vector<double>(num_extra, 1.0));
  const int num_position_cols = system.num_position_cols;
  for (size_t k = 0; k < pairs.size(); ++k) {
    x(num_position_cols + k) =
        pairs[k].direction.dot(CenterIn(x, column, pairs[k].j) - CenterIn(x, column, pairs[k].i));
  }
  return ProjectScales(x, system);
}

}  // namespace

namespace {

// Solves the largest connected set of `constraints` and `pairs` in the L1 sense; the images it
// leaves out go to result->unconstrained_images. Its gauge and scale are those of the header.
// `x` and `column` are the solution and each image's camera index in it.
void SolveConnected(const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                    std::vector<Constraint>* constraints, std::vector<PairRow>* pairs,
                    const std::vector<PosePriorInModel>& priors,
                    const TranslationAveragingOptions& options, TranslationAveragingResult* result,
                    Eigen::VectorXd* x, std::map<uint32_t, int>* column) {
  result->unconstrained_images.clear();
  const std::vector<uint32_t> solved =
      LargestConnectedImages(rotations, *constraints, *pairs, &result->unconstrained_images);
  if (solved.size() < 2)
    throw StageFailure("translation averaging: fewer than two cameras connected");
  // Priors of positioned cameras; with any, they fix the gauge and no camera is held.
  const std::vector<PosePriorInModel> used_priors = PriorsOfSolvedImages(solved, priors);
  const bool has_priors = !used_priors.empty();
  column->clear();
  result->gauge_image_id = has_priors ? 0 : solved.front();
  for (size_t i = 0; i < solved.size(); ++i) {
    (*column)[solved[i]] = static_cast<int>(i) - (has_priors ? 0 : 1);
  }
  constraints->erase(std::remove_if(constraints->begin(), constraints->end(),
                                    [&](const Constraint& c) { return !column->count(c.a.from); }),
                     constraints->end());
  pairs->erase(std::remove_if(pairs->begin(), pairs->end(),
                              [&](const PairRow& pair) { return !column->count(pair.i); }),
               pairs->end());
  const int num_cameras = static_cast<int>(solved.size()) - (has_priors ? 0 : 1);
  const StackedSystem system =
      AssembleSystem(*constraints, *pairs, used_priors, *column, num_cameras, options);
  int iterations = 0;
  PositionSolver solver(system, options);
  *x = LeastSquaresStart(system, *pairs, *column, &solver);
  *x = options.solver == TranslationSolver::kIrls
           ? SolveByIrls(system, *x, options, &solver, &iterations)
           : SolveByAdmm(system, *x, options, &iterations);
  result->num_solver_iterations += iterations;
  result->num_factorizations += solver.num_factorizations();
  result->l1_cost = (system.B * *x).lpNorm<1>();
  result->num_priors_used = static_cast<int>(used_priors.size());
}

// Removes the pair rows whose direction the solution misses by more than the threshold (an angle
// from their median: what noise gives here) and the track constraints whose residual exceeds
// theirs; returns how many were removed. An L1 solution leaves wrong rows with large residuals
// and the others near zero, so after removal the rest decide alone: a wrong direction then moves
// the solution no more than a missing one would.
int RejectOutlierRows(const Eigen::VectorXd& x, const std::map<uint32_t, int>& column,
                      const TranslationAveragingOptions& options,
                      std::vector<Constraint>* constraints, std::vector<PairRow>* pairs,
                      std::vector<RejectedPairRow>* rejected_pairs) {
  std::vector<double> angles(pairs->size());
  for (size_t k = 0; k < pairs->size(); ++k) {
    const PairRow& pair = (*pairs)[k];
    const Eigen::Vector3d baseline = CenterIn(x, column, pair.j) - CenterIn(x, column, pair.i);
    angles[k] = std::atan2(baseline.cross(pair.direction).norm(), baseline.dot(pair.direction));
  }
  const double max_angle = std::max(options.rejection_min_angle_deg * kDegToRad,
                                    options.rejection_multiplier * Median(angles));
  std::vector<double> residuals(constraints->size());
  for (size_t k = 0; k < constraints->size(); ++k) {
    const Constraint& c = (*constraints)[k];
    const auto predicted = [&](const PointPrediction& p) {
      const Eigen::Vector3d from = CenterIn(x, column, p.from);
      return Eigen::Vector3d(from + p.M * (CenterIn(x, column, p.to) - from));
    };
    residuals[k] = c.weight * (predicted(c.a) - predicted(c.b)).norm();
  }
  const double max_residual =
      residuals.empty() ? 0.0 : options.rejection_multiplier * Median(residuals);
  const size_t num_before = pairs->size() + constraints->size();
  std::vector<PairRow> kept_pairs;
  for (size_t k = 0; k < pairs->size(); ++k) {
    const PairRow& pair = (*pairs)[k];
    if (angles[k] <= max_angle) {
      kept_pairs.push_back(pair);
    } else {
      rejected_pairs->push_back({pair.i, pair.j, angles[k] * kRadToDeg, max_angle * kRadToDeg});
    }
  }
  std::vector<Constraint> kept_constraints;
  for (size_t k = 0; k < constraints->size(); ++k) {
    if (!(max_residual > 0 && residuals[k] > max_residual)) {
      kept_constraints.push_back((*constraints)[k]);
    }
  }
  *pairs = std::move(kept_pairs);
  *constraints = std::move(kept_constraints);
  return static_cast<int>(num_before - pairs->size() - constraints->size());
}

}  // namespace

TranslationAveragingResult AverageTranslations(
    const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<PairDirection>& pair_directions, const std::vector<Track>& tracks,
    const KeypointBearings& bearings, const TranslationAveragingOptions& options,
    const std::vector<PosePriorInModel>& priors) {
  options.Check();
  Timer timer;
  TranslationAveragingResult result;
  const DirectionTable directions(pair_directions);
  std::vector<Constraint> constraints =
      BuildConstraints(rotations, directions, tracks, bearings, options, &result.num_tracks_used);
  std::vector<PairRow> pairs = UsablePairRows(rotations, pair_directions);
  if (pairs.empty()) {
    throw StageFailure("translation averaging: no pair direction (every pair is a pure rotation?)");
  }
  Eigen::VectorXd x;
  std::map<uint32_t, int> column;  // image id -> camera index (the gauge camera: -1)
  SolveConnected(rotations, &constraints, &pairs, priors, options, &result, &x, &column);
  for (int round = 0; round < options.max_rejection_rounds; ++round) {
    const int rejected =
        RejectOutlierRows(x, column, options, &constraints, &pairs, &result.rejected_pair_rows);
    if (rejected == 0 || pairs.empty()) break;
    result.num_rejected_rows += rejected;
    SolveConnected(rotations, &constraints, &pairs, priors, options, &result, &x, &column);
  }

  // The documented scale: mean projected pair baseline = 1.
  double projected = 0.0;
  for (const PairRow& pair : pairs) {
    projected += pair.direction.dot(CenterIn(x, column, pair.j) - CenterIn(x, column, pair.i));
  }
  if (!(projected > 0)) {
    throw StageFailure("translation averaging: the solution does not fit the pair directions");
  }
  result.num_constraints = static_cast<int>(constraints.size() + pairs.size());
  // With priors the solution is already in their frame and units.
  const bool has_priors = result.num_priors_used > 0;
  const double scale = has_priors ? 1.0 : static_cast<double>(pairs.size()) / projected;
  for (const auto& [image_id, camera] : column) {
    (void)camera;
    result.centers[image_id] = scale * CenterIn(x, column, image_id);
  }
  result.seconds = timer.ElapsedSeconds();
  return result;
}

}  // namespace ramap
