#include "ramap/averaging/direction_consistency.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "ramap/util/option_check.h"
#include "ramap/util/statistics.h"

namespace ramap {

void DirectionConsistencyOptions::Check() const {
  CheckOptionValues(DirectionConsistencyOptionTable(), *this);
  // The settings no command line option reaches.
  CheckOption(max_num_cycles >= min_num_cycles, "DirectionConsistencyOptions::max_num_cycles",
              ">= --TranslationAveraging.direction_min_num_cycles", max_num_cycles);
  CheckOption(num_rounds >= 1, "DirectionConsistencyOptions::num_rounds", ">= 1", num_rounds);
}

double AngleToCone(const Eigen::Vector3d& direction, const Eigen::Vector3d& u,
                   const Eigen::Vector3d& v) {
  const auto angle = [&](const Eigen::Vector3d& x) {
    return std::atan2(direction.cross(x).norm(), direction.dot(x));
  };
  double best = std::min(angle(u), angle(v));
  // Inside the cone's wedge, the nearest direction is the projection onto its plane.
  const double uv = u.dot(v);
  const double determinant = 1.0 - uv * uv;
  if (determinant > 1e-12) {
    const double uw = u.dot(direction);
    const double vw = v.dot(direction);
    const double s = (uw - uv * vw) / determinant;
    const double t = (vw - uv * uw) / determinant;
    if (s >= 0 && t >= 0) best = std::min(best, angle(s * u + t * v));
  }
  return best;
}

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// The pairs with a direction, by image: (other image, index of the direction), by other image.
using Adjacency = std::unordered_map<uint32_t, std::vector<std::pair<uint32_t, size_t>>>;

Adjacency BuildAdjacency(const std::vector<PairDirection>& directions,
                         const std::vector<bool>& active) {
  Adjacency adjacency;
  for (size_t k = 0; k < directions.size(); ++k) {
    if (!active[k]) continue;
    adjacency[directions[k].image_id1].emplace_back(directions[k].image_id2, k);
    adjacency[directions[k].image_id2].emplace_back(directions[k].image_id1, k);
  }
  for (auto& [image_id, neighbours] : adjacency) std::sort(neighbours.begin(), neighbours.end());
  return adjacency;
}

// Unit direction of c_to - c_from from the stored direction of their pair.
Eigen::Vector3d From(const PairDirection& pair, uint32_t from) {
  return pair.image_id1 == from ? pair.direction : Eigen::Vector3d(-pair.direction);
}

// A cycle's legs tell the direction apart from its opposite only while they point roughly the
// same way: a leg back past the first image and one forward past the second span half a plane,
// which holds both. Cycles with legs further apart than this are not counted.
constexpr double kMaxLegSpreadCos = 0.0;  // 90 deg

bool Informative(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return u.dot(v) >= kMaxLegSpreadCos;
}

// The angle (radians) from `direction` to the cone of three unit legs: zero inside, else the
// angle to the nearest face (the cone of two of them).
double AngleToCone3(const Eigen::Vector3d& direction, const Eigen::Vector3d& u,
                    const Eigen::Vector3d& v, const Eigen::Vector3d& x) {
  Eigen::Matrix3d legs;
  legs << u, v, x;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(legs);
  if (lu.isInvertible() && (lu.solve(direction).array() >= 0).all()) return 0.0;
  return std::min(
      {AngleToCone(direction, u, v), AngleToCone(direction, v, x), AngleToCone(direction, u, x)});
}

// The pairs with a direction, for the look-ups of 4-cycles.
using PairIndex = std::unordered_map<uint64_t, size_t>;

uint64_t PairKey(uint32_t a, uint32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// One cycle closed by a direction: its residual (radians) and the other directions on it.
struct Cycle {
  double residual = 0.0;
  std::array<size_t, 3> legs{};
  int num_legs = 0;
};

// The cycles that direction k closes: triangles a -> c -> b, and when they are fewer than
// min_num_cycles, quadrilaterals a -> c -> d -> b (a pair that skips more frames than the others
// match has no triangle).
std::vector<Cycle> Cycles(const std::vector<PairDirection>& directions, size_t k,
                          const Adjacency& adjacency, const PairIndex& index,
                          const DirectionConsistencyOptions& options) {
  const PairDirection& pair = directions[k];
  const uint32_t a = pair.image_id1;
  const uint32_t b = pair.image_id2;
  const Eigen::Vector3d w = pair.direction.normalized();
  const auto& of_a = adjacency.at(a);
  const auto& of_b = adjacency.at(b);
  std::vector<Cycle> cycles;
  const auto full = [&] { return static_cast<int>(cycles.size()) >= options.max_num_cycles; };
  for (auto x = of_a.begin(), y = of_b.begin(); x != of_a.end() && y != of_b.end() && !full();) {
    if (x->first < y->first) {
      ++x;
    } else if (y->first < x->first) {
      ++y;
    } else {
      const Eigen::Vector3d u = From(directions[x->second], a).normalized();
      const Eigen::Vector3d v = (-From(directions[y->second], b)).normalized();
      if (Informative(u, v)) cycles.push_back({AngleToCone(w, u, v), {x->second, y->second}, 2});
      ++x;
      ++y;
    }
  }
  if (static_cast<int>(cycles.size()) >= options.min_num_cycles) return cycles;
  for (const auto& [c, ac] : of_a) {
    if (c == b) continue;
    const Eigen::Vector3d u = From(directions[ac], a).normalized();
    for (const auto& [d, db] : of_b) {
      if (d == a || d == c || full()) continue;
      const auto cd = index.find(PairKey(c, d));
      if (cd == index.end()) continue;
      const Eigen::Vector3d v = From(directions[cd->second], c).normalized();
      const Eigen::Vector3d x = (-From(directions[db], b)).normalized();
      if (Informative(u, v) && Informative(v, x) && Informative(u, x)) {
        cycles.push_back({AngleToCone3(w, u, v, x), {ac, cd->second, db}, 3});
      }
    }
  }
  return cycles;
}

// A direction's test: the lower quartile of its cycles' residuals (radians), their number, and the
// directions on them. A wrong direction spoils every cycle it closes, a right one only those it
// shares with a wrong one: the lower quartile separates the two where a median would also blame a
// right pair whose few cycles mostly pass through a wrong one.
struct Tested {
  double consistency = 0.0;
  int num_cycles = 0;
  std::vector<size_t> legs;
};

Tested Test(const std::vector<PairDirection>& directions, size_t k, const Adjacency& adjacency,
            const PairIndex& index, const DirectionConsistencyOptions& options) {
  const std::vector<Cycle> cycles = Cycles(directions, k, adjacency, index, options);
  Tested tested;
  tested.num_cycles = static_cast<int>(cycles.size());
  if (cycles.empty()) return tested;
  std::vector<double> residuals;
  for (const Cycle& cycle : cycles) {
    residuals.push_back(cycle.residual);
    tested.legs.insert(tested.legs.end(), cycle.legs.begin(), cycle.legs.begin() + cycle.num_legs);
  }
  const auto quartile = residuals.begin() + residuals.size() / 4;
  std::nth_element(residuals.begin(), quartile, residuals.end());
  tested.consistency = *quartile;
  return tested;
}

// The active directions' tests and the pair index they look cycles up in.
std::vector<Tested> TestActive(const std::vector<PairDirection>& directions,
                               const std::vector<bool>& active,
                               const DirectionConsistencyOptions& options) {
  const Adjacency adjacency = BuildAdjacency(directions, active);
  PairIndex index;
  for (size_t k = 0; k < directions.size(); ++k) {
    if (active[k]) index[PairKey(directions[k].image_id1, directions[k].image_id2)] = k;
  }
  std::vector<Tested> tests(directions.size());
  for (size_t k = 0; k < directions.size(); ++k) {
    if (active[k]) tests[k] = Test(directions, k, adjacency, index, options);
  }
  return tests;
}

// The threshold (degrees) of the first round, from the tested directions' consistencies.
double Threshold(const std::vector<Tested>& tests, const std::vector<bool>& active,
                 const DirectionConsistencyOptions& options, DirectionConsistencyResult* result) {
  std::vector<double> tested;
  for (size_t k = 0; k < tests.size(); ++k) {
    if (active[k] && tests[k].num_cycles >= options.min_num_cycles) {
      tested.push_back(tests[k].consistency * kRadToDeg);
    }
  }
  result->num_tested = static_cast<int>(tested.size());
  result->median_consistency_deg = tested.empty() ? 0.0 : Median(tested);
  double threshold = options.max_residual_deg;
  if (options.mode == DirectionCheckMode::kAdaptive) {
    threshold = std::clamp(options.threshold_multiplier * result->median_consistency_deg,
                           options.min_threshold_deg, options.max_residual_deg);
  }
  result->threshold_deg = threshold;
  return threshold;
}

// One round: the directions above the threshold are rejected, worst first; one that shares a
// cycle with a direction rejected in this round waits for the next, where its cycles are formed
// without it. Returns whether any direction was rejected.
bool RejectRound(const std::vector<PairDirection>& directions, const std::vector<Tested>& tests,
                 double threshold_deg, int round, const DirectionConsistencyOptions& options,
                 std::vector<bool>* active, DirectionConsistencyResult* result) {
  std::vector<size_t> candidates;
  for (size_t k = 0; k < directions.size(); ++k) {
    if ((*active)[k] && tests[k].num_cycles >= options.min_num_cycles &&
        tests[k].consistency * kRadToDeg > threshold_deg) {
      candidates.push_back(k);
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](size_t x, size_t y) { return tests[x].consistency > tests[y].consistency; });
  std::vector<bool> rejected_now(directions.size(), false);
  bool any = false;
  for (const size_t k : candidates) {
    const std::vector<size_t>& legs = tests[k].legs;
    if (std::any_of(legs.begin(), legs.end(), [&](size_t leg) { return rejected_now[leg]; })) {
      continue;
    }
    rejected_now[k] = true;
    (*active)[k] = false;
    any = true;
    result->rejected.push_back({directions[k].image_id1, directions[k].image_id2,
                                tests[k].consistency * kRadToDeg, threshold_deg,
                                tests[k].num_cycles, round});
  }
  return any;
}

}  // namespace

DirectionConsistencyResult CheckDirectionCycles(const std::vector<PairDirection>& directions,
                                                const DirectionConsistencyOptions& options) {
  options.Check();
  DirectionConsistencyResult result;
  std::vector<bool> active(directions.size(), true);
  if (options.mode != DirectionCheckMode::kOff) {
    double threshold = -1.0;
    for (int round = 1; round <= options.num_rounds; ++round) {
      const std::vector<Tested> tests = TestActive(directions, active, options);
      if (round == 1) threshold = Threshold(tests, active, options, &result);
      if (!RejectRound(directions, tests, threshold, round, options, &active, &result)) break;
    }
  }
  for (size_t k = 0; k < directions.size(); ++k) {
    if (active[k]) result.kept.push_back(directions[k]);
  }
  return result;
}

}  // namespace ramap
