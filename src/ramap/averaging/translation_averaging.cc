#include "ramap/averaging/translation_averaging.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <unordered_map>

#include "ramap/util/timer.h"

namespace ramap {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
// Inverse iterations for the least-squares start (converges in a few dozen on our problems).
constexpr int kMaxInverseIterations = 100;

uint64_t PairKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// The point of a track as predicted from the pair (from, to): X = c_from + M (c_to - c_from).
struct PointPrediction {
  uint32_t from = 0;
  uint32_t to = 0;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  double depth_ratio = 0.0;  // |X - c_from| / |c_to - c_from|
  double ray_angle = 0.0;    // angle between the two rays, radians
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
  Eigen::Matrix<double, 3, 2> design;
  design.col(0) = ray_from;
  design.col(1) = -ray_to;
  const Eigen::Vector2d depths = design.colPivHouseholderQr().solve(*baseline);
  if (!(depths(0) > 0 && depths(1) > 0)) return std::nullopt;
  PointPrediction prediction;
  prediction.from = from;
  prediction.to = to;
  prediction.depth_ratio = depths(0);
  prediction.ray_angle = ray_angle;
  prediction.M =
      depths(0) * Eigen::Quaterniond::FromTwoVectors(*baseline, ray_from).toRotationMatrix();
  return prediction;
}

// One 3-row block: prediction_a(c) - prediction_b(c) = 0, scaled to baseline units.
struct Constraint {
  PointPrediction a;
  PointPrediction b;
  double weight = 1.0;
};

class UnionFind {
 public:
  uint32_t Find(uint32_t x) {
    auto it = parent_.find(x);
    if (it == parent_.end()) {
      parent_[x] = x;
      return x;
    }
    if (it->second == x) return x;
    const uint32_t root = Find(it->second);
    parent_[x] = root;
    return root;
  }
  void Union(uint32_t a, uint32_t b) { parent_[Find(a)] = Find(b); }

 private:
  std::unordered_map<uint32_t, uint32_t> parent_;
};

std::vector<Constraint> BuildConstraints(const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                         const DirectionTable& directions,
                                         const std::vector<TranslationTrack>& tracks,
                                         const TranslationAveragingOptions& options,
                                         int* num_tracks_used) {
  const double min_angle = options.min_triangulation_angle_deg * kDegToRad;
  // Longer tracks first: they carry more constraints per point.
  std::vector<size_t> order(tracks.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return tracks[x].size() > tracks[y].size(); });
  if (static_cast<int>(order.size()) > options.max_num_tracks) order.resize(options.max_num_tracks);

  std::vector<Constraint> constraints;
  std::unordered_map<uint32_t, int> usage;  // constraints per camera so far
  *num_tracks_used = 0;
  for (const size_t track_index : order) {
    // Of a long track, use the cameras with the fewest constraints so far, so that every camera
    // gets its share and none is left out by the cap.
    std::vector<const TrackObservation*> usable;
    for (const TrackObservation& observation : tracks[track_index]) {
      if (rotations.count(observation.image_id) && observation.bearing.allFinite()) {
        usable.push_back(&observation);
      }
    }
    std::stable_sort(usable.begin(), usable.end(), [&](const auto* x, const auto* y) {
      return usage[x->image_id] < usage[y->image_id];
    });
    std::vector<uint32_t> ids;
    std::vector<Eigen::Vector3d> rays;
    for (const TrackObservation* observation : usable) {
      if (std::find(ids.begin(), ids.end(), observation->image_id) != ids.end()) continue;
      ids.push_back(observation->image_id);
      rays.push_back(
          (rotations.at(observation->image_id).conjugate() * observation->bearing).normalized());
      if (static_cast<int>(ids.size()) >= options.max_observations_per_track) break;
    }
    if (ids.size() < 2) continue;
    // Reference: the best-conditioned pair (widest ray angle).
    std::optional<PointPrediction> reference;
    size_t ref_a = 0, ref_b = 0;
    for (size_t a = 0; a < ids.size(); ++a) {
      for (size_t b = 0; b < ids.size(); ++b) {
        if (a == b) continue;
        const auto prediction =
            PredictPoint(ids[a], ids[b], rays[a], rays[b], directions, min_angle);
        if (prediction && (!reference || prediction->ray_angle > reference->ray_angle)) {
          reference = prediction;
          ref_a = a;
          ref_b = b;
        }
      }
    }
    if (!reference) continue;
    int added = 0;
    for (size_t k = 0; k < ids.size(); ++k) {
      if (k == ref_a) continue;
      // Camera k predicts X from its best-conditioned pair with any other camera of the track
      // (a sequence frame often has no verified pair with the reference cameras themselves).
      std::optional<PointPrediction> best;
      for (size_t partner = 0; partner < ids.size(); ++partner) {
        if (partner == k) continue;
        const auto prediction =
            PredictPoint(ids[k], ids[partner], rays[k], rays[partner], directions, min_angle);
        if (prediction && (!best || prediction->ray_angle > best->ray_angle)) best = prediction;
      }
      if (!best) continue;
      Constraint constraint;
      constraint.a = *reference;
      constraint.b = *best;
      // Residuals are point displacements; dividing by the depth ratio expresses them in baselines,
      // so that far points do not dominate.
      constraint.weight = 1.0 / std::max({1.0, reference->depth_ratio, best->depth_ratio});
      constraints.push_back(constraint);
      for (const uint32_t id : {ids[k], best->to}) ++usage[id];
      ++added;
    }
    if (added > 0) ++*num_tracks_used;
  }
  return constraints;
}

Eigen::VectorXd SoftThreshold(const Eigen::VectorXd& v, double kappa) {
  return (v.array() - kappa).max(0.0) - (-v.array() - kappa).max(0.0);
}

}  // namespace

void TranslationAveragingOptions::Check() const {
  if (!(min_triangulation_angle_deg > 0 && min_triangulation_angle_deg < 90)) {
    throw std::invalid_argument("min_triangulation_angle_deg must be in (0, 90)");
  }
  if (max_observations_per_track < 2) throw std::invalid_argument("max_observations_per_track < 2");
  if (max_num_tracks < 1) throw std::invalid_argument("max_num_tracks must be >= 1");
  if (!(admm_rho > 0)) throw std::invalid_argument("admm_rho must be > 0");
  if (!(admm_relaxation > 0 && admm_relaxation < 2)) {
    throw std::invalid_argument("admm_relaxation must be in (0, 2)");
  }
  if (max_admm_iterations < 0) throw std::invalid_argument("max_admm_iterations must be >= 0");
  if (!(admm_tolerance > 0)) throw std::invalid_argument("admm_tolerance must be > 0");
  if (!(admm_cost_tolerance >= 0)) throw std::invalid_argument("admm_cost_tolerance must be >= 0");
  if (!(admm_relative_tolerance >= 0))
    throw std::invalid_argument("admm_relative_tolerance must be >= 0");
}

TranslationAveragingResult AverageTranslations(
    const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<PairDirection>& pair_directions, const std::vector<TranslationTrack>& tracks,
    const TranslationAveragingOptions& options) {
  options.Check();
  Timer timer;
  TranslationAveragingResult result;
  const DirectionTable directions(pair_directions);
  std::vector<Constraint> constraints =
      BuildConstraints(rotations, directions, tracks, options, &result.num_tracks_used);

  // Solve the largest set of cameras that the constraints connect.
  UnionFind components;
  std::set<uint32_t> constrained;
  for (const Constraint& c : constraints) {
    for (const uint32_t id : {c.a.to, c.b.from, c.b.to}) components.Union(c.a.from, id);
    constrained.insert({c.a.from, c.a.to, c.b.from, c.b.to});
  }
  if (constrained.empty()) {
    throw std::runtime_error(
        "translation averaging: no usable track constraint (too little parallax?)");
  }
  std::map<uint32_t, int> component_size;
  for (const uint32_t image_id : constrained) ++component_size[components.Find(image_id)];
  const uint32_t root =
      std::max_element(component_size.begin(), component_size.end(),
                       [](const auto& x, const auto& y) { return x.second < y.second; })
          ->first;
  std::vector<uint32_t> solved;  // positioned image ids, increasing; solved[0] is the gauge camera
  for (const auto& [image_id, rotation] : rotations) {
    (void)rotation;
    if (constrained.count(image_id) && components.Find(image_id) == root) {
      solved.push_back(image_id);
    } else {
      result.unconstrained_images.push_back(image_id);
    }
  }
  if (solved.size() < 2)
    throw std::runtime_error("translation averaging: fewer than two cameras connected");
  std::map<uint32_t, int> column;  // image id -> camera index (the gauge camera: -1)
  result.gauge_image_id = solved.front();
  for (size_t i = 0; i < solved.size(); ++i) column[solved[i]] = static_cast<int>(i) - 1;
  constraints.erase(std::remove_if(constraints.begin(), constraints.end(),
                                   [&](const Constraint& c) { return !column.count(c.a.from); }),
                    constraints.end());

  // A x = 0 with x the stacked centres of all cameras but the gauge camera (fixed at the origin).
  const int num_rows = 3 * static_cast<int>(constraints.size());
  const int num_cols = 3 * (static_cast<int>(solved.size()) - 1);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(constraints.size() * 36);
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
  Eigen::SparseMatrix<double> A(num_rows, num_cols);
  A.setFromTriplets(triplets.begin(), triplets.end());

  // Gauge of the solve: the first camera at the origin (its columns are left out) and ||x||_2 fixed,
  // as in Cui et al. The radius sqrt(#cameras) makes coordinates O(1), so that rho and the
  // tolerances mean the same on every problem size. A sphere rather than a linear normalisation keeps L1 from putting all of the
  // scale on one camera while the rest collapse to the origin.
  Eigen::SparseMatrix<double> normal = A.transpose() * A;
  // A tiny ridge keeps the factorisation defined where a camera is only weakly constrained.
  Eigen::SparseMatrix<double> ridge(num_cols, num_cols);
  ridge.setIdentity();
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> least_squares;
  least_squares.compute(normal + 1e-10 * ridge);
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> admm_step;
  admm_step.compute(normal + ridge);
  if (least_squares.info() != Eigen::Success || admm_step.info() != Eigen::Success) {
    throw std::runtime_error("translation averaging: factorisation failed");
  }

  // Start: the least-squares solution on the sphere, the eigenvector of A^T A of the smallest
  // eigenvalue, by inverse iteration.
  const double radius = std::sqrt(static_cast<double>(solved.size()));
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(num_cols, 1.0, 2.0).normalized();
  for (int k = 0; k < kMaxInverseIterations; ++k) {
    const Eigen::VectorXd next = least_squares.solve(x).normalized();
    const double change = std::min((next - x).norm(), (next + x).norm());
    x = next;
    if (change < 1e-12) break;
  }
  x *= radius;

  // ADMM on min ||z||_1 + [x on the sphere] s.t. z = A y, x = y (scaled form; Boyd et al. 2011).
  // The y-update's matrix A^T A + I does not depend on rho, so it is factored once.
  Eigen::VectorXd y = x;
  Eigen::VectorXd z = A * y;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(num_rows);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(num_cols);
  const double rho = options.admm_rho;
  const double tolerance_primal =
      options.admm_tolerance * std::sqrt(static_cast<double>(num_rows + num_cols));
  const double tolerance_dual = options.admm_tolerance * std::sqrt(static_cast<double>(num_cols));
  constexpr int kCostCheckInterval = 50;
  double previous_cost = std::numeric_limits<double>::infinity();
  int iteration = 0;
  for (; iteration < options.max_admm_iterations; ++iteration) {
    y = admm_step.solve(A.transpose() * (z - u) + (x - w));
    const Eigen::VectorXd Ay = A * y;
    const Eigen::VectorXd Ay_relaxed =
        options.admm_relaxation * Ay + (1.0 - options.admm_relaxation) * z;
    const Eigen::VectorXd z_previous = z;
    const Eigen::VectorXd x_previous = x;
    z = SoftThreshold(Ay_relaxed + u, 1.0 / rho);
    x = radius * (y + w).normalized();
    u += Ay_relaxed - z;
    w += y - x;
    const double primal = std::sqrt((Ay - z).squaredNorm() + (y - x).squaredNorm());
    const double dual =
        rho * (A.transpose() * (z - z_previous) + (x - x_previous)).norm();
    // Stopping rule of Boyd et al. 2011, sec. 3.3.1: absolute plus relative tolerances.
    const double relative = options.admm_relative_tolerance;
    if (primal < tolerance_primal + relative * std::max(Ay.norm(), z.norm()) &&
        dual < tolerance_dual + relative * rho * (A.transpose() * u + w).norm()) {
      ++iteration;
      break;
    }
    // ADMM's residuals shrink slowly once the L1 cost has settled (its tail is long): stop when the
    // cost changed by less than admm_cost_tolerance over the last check window.
    if (iteration % kCostCheckInterval == kCostCheckInterval - 1) {
      const double cost = (A * x).lpNorm<1>();
      if (std::abs(previous_cost - cost) <= options.admm_cost_tolerance * cost) {
        ++iteration;
        break;
      }
      previous_cost = cost;
    }
  }

  // The sphere leaves the sign free: the pair directions choose it. Then the documented scale,
  // mean projected pair baseline = 1.
  double projected = 0.0;
  int num_pairs = 0;
  for (const PairDirection& pair : pair_directions) {
    const auto i = column.find(pair.image_id1), j = column.find(pair.image_id2);
    if (i == column.end() || j == column.end()) continue;
    const Eigen::Vector3d ci = i->second < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(x.segment<3>(3 * i->second));
    const Eigen::Vector3d cj = j->second < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(x.segment<3>(3 * j->second));
    projected += pair.direction.normalized().dot(cj - ci);
    ++num_pairs;
  }
  if (num_pairs == 0 || !(std::abs(projected) > 0)) {
    throw std::runtime_error("translation averaging: the solution does not fit the pair directions");
  }
  x *= num_pairs / projected;
  result.num_admm_iterations = iteration;
  result.l1_cost = (A * x).lpNorm<1>();
  result.num_constraints = static_cast<int>(constraints.size());
  for (const uint32_t image_id : solved) {
    const int cam = column.at(image_id);
    result.centers[image_id] =
        cam < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(x.segment<3>(3 * cam));
  }
  result.seconds = timer.ElapsedSeconds();
  return result;
}

}  // namespace ramap
