#include "ramap/averaging/pair_directions.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ramap/geometry/rotation.h"
#include "ramap/geometry/triangulation.h"
#include "ramap/util/option_check.h"

namespace ramap {

void PairDirectionOptions::Check() const { CheckOptionValues(PairDirectionOptionTable(), *this); }

namespace {

// The coplanarity normals of a pair's matches and their rays, in camera 1's frame.
struct PairRays {
  std::vector<Eigen::Vector3d> normals;  // unit
  std::vector<Eigen::Vector3d> rays1;
  std::vector<Eigen::Vector3d> rays2;
};

// Computed in camera 1's frame (one rotation per match instead of two; the coplanarity, the weights
// and the depths' signs do not depend on the frame). The rays are not normalised: a ray's length
// changes neither its normal's direction nor the sign of its depth; the ray-angle test scales by
// the lengths instead.
PairRays CoplanarityNormals(const Eigen::Matrix3d& cam1_from_cam2,
                            const std::vector<Eigen::Vector3d>& bearings1,
                            const std::vector<Eigen::Vector3d>& bearings2,
                            double min_ray_angle_deg) {
  const double min_sin = std::sin(min_ray_angle_deg * kDegToRad);
  const double min_sin_squared = min_sin * min_sin;
  PairRays pair;
  const size_t num_matches = std::min(bearings1.size(), bearings2.size());
  pair.normals.reserve(num_matches);
  pair.rays1.reserve(num_matches);
  pair.rays2.reserve(num_matches);
  for (size_t k = 0; k < num_matches; ++k) {
    const Eigen::Vector3d& d1 = bearings1[k];
    const Eigen::Vector3d d2 = cam1_from_cam2 * bearings2[k];
    const Eigen::Vector3d n = d1.cross(d2);
    const double n_squared = n.squaredNorm();
    if (!(n_squared >= min_sin_squared * d1.squaredNorm() * d2.squaredNorm()) || n_squared == 0.0)
      continue;  // also drops non-finite rays, for which the comparison is false
    pair.normals.push_back(n / std::sqrt(n_squared));
    pair.rays1.push_back(d1);
    pair.rays2.push_back(d2);
  }
  return pair;
}

// Cauchy weight of a coplanarity residual n . t at a scale (the sine of residual_scale_deg) whose
// inverse square is given: one division per weight instead of two, in the rounds' inner loop.
double CauchyWeight(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction,
                    double inverse_scale_squared) {
  const double residual = normal.dot(direction);
  return 1.0 / (1.0 + residual * residual * inverse_scale_squared);
}

// The direction minimises sum w (n . t)^2: the eigenvector of the smallest eigenvalue. Each round's
// weights come from the last direction (none in the first round without a start). The rounds stop
// early once the direction moves by less than 1e-6 rad (|cos| within 5e-13 of 1): later rounds
// could only move it by as little, far below the matches' noise. Few pairs settle that early, so
// the stop saves little time, but it costs nothing.
Eigen::Vector3d ReweightedDirection(const std::vector<Eigen::Vector3d>& normals,
                                    const std::optional<Eigen::Vector3d>& start, double scale,
                                    int num_reweighting_rounds) {
  const double inverse_scale_squared = 1.0 / (scale * scale);
  Eigen::Vector3d direction = start.value_or(Eigen::Vector3d::Zero());
  const int first_round = start ? 1 : 0;
  for (int round = first_round; round <= num_reweighting_rounds + first_round; ++round) {
    // The scatter's lower triangle, the only one the eigensolver reads.
    double xx = 0, yx = 0, zx = 0, yy = 0, zy = 0, zz = 0;
    for (const Eigen::Vector3d& n : normals) {
      const double w = round == 0 ? 1.0 : CauchyWeight(n, direction, inverse_scale_squared);
      const double wx = w * n.x(), wy = w * n.y(), wz = w * n.z();
      xx += wx * n.x(), yx += wy * n.x(), zx += wz * n.x();
      yy += wy * n.y(), zy += wz * n.y(), zz += wz * n.z();
    }
    Eigen::Matrix3d scatter;
    scatter << xx, 0, 0, yx, yy, 0, zx, zy, zz;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    const Eigen::Vector3d previous = direction;
    direction = solver.eigenvectors().col(0);
    if (round > 0 && std::abs(previous.dot(direction)) > 1.0 - 5e-13) break;
  }
  return direction;
}

// How many normals agree with the direction (residual within the Cauchy scale: weight >= 1/2).
int NumAgreeing(const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector3d& direction,
                double scale) {
  return static_cast<int>(std::count_if(normals.begin(), normals.end(), [&](const auto& normal) {
    return std::abs(normal.dot(direction)) <= scale;
  }));
}

// The start most normals agree with among `num_starts` two-match directions n_a x n_b (the
// direction of a pair of correct matches), a and b evenly spaced and half the list apart: a
// deterministic minimal-sample search, as RANSAC would do with random samples.
std::optional<Eigen::Vector3d> SampledStart(const std::vector<Eigen::Vector3d>& normals,
                                            double scale, int num_starts) {
  std::optional<Eigen::Vector3d> best;
  int best_agreeing = 0;
  const size_t n = normals.size();
  for (int k = 0; k < num_starts; ++k) {
    const size_t a = k * n / num_starts;
    const size_t b = (a + n / 2 + k) % n;
    const Eigen::Vector3d candidate = normals[a].cross(normals[b]);
    if (a == b || candidate.norm() < 1e-6) continue;  // (nearly) the same plane twice
    const int agreeing = NumAgreeing(normals, candidate.normalized(), scale);
    if (agreeing > best_agreeing) best_agreeing = agreeing, best = candidate.normalized();
  }
  return best;
}

// Sign by cheirality: with c2 - c1 = t, a match triangulates at c1 + l1 d1 = c2 + l2 d2, and both
// depths must be positive for the right sign. +1 or -1; 0 when the vote is too small or split.
int CheiralSign(const PairRays& pair, const Eigen::Vector3d& direction, double scale,
                const PairDirectionOptions& options) {
  int votes_for = 0, votes_against = 0;
  for (size_t k = 0; k < pair.rays1.size(); ++k) {
    // Wrong matches (residual beyond the Cauchy scale) abstain.
    if (std::abs(pair.normals[k].dot(direction)) > scale) continue;
    const std::optional<Eigen::Vector2d> depths =
        TwoRayDepths(pair.rays1[k], pair.rays2[k], direction);
    if (!depths) continue;  // parallel rays: no depth
    if ((*depths)(0) > 0 && (*depths)(1) > 0) ++votes_for;
    if ((*depths)(0) < 0 && (*depths)(1) < 0) ++votes_against;
  }
  const int votes = votes_for + votes_against;
  if (votes < options.min_num_matches / 2) return 0;
  if (votes_for >= options.min_cheirality_ratio * votes) return 1;
  if (votes_against >= options.min_cheirality_ratio * votes) return -1;
  return 0;
}

}  // namespace

std::optional<Eigen::Vector3d> EstimatePairDirection(const Eigen::Quaterniond& rotation1,
                                                     const Eigen::Quaterniond& rotation2,
                                                     const std::vector<Eigen::Vector3d>& bearings1,
                                                     const std::vector<Eigen::Vector3d>& bearings2,
                                                     const PairDirectionOptions& options) {
  const PairRays pair = CoplanarityNormals((rotation1 * rotation2.conjugate()).toRotationMatrix(),
                                           bearings1, bearings2, options.min_ray_angle_deg);
  if (static_cast<int>(pair.normals.size()) < options.min_num_matches) return std::nullopt;
  const double scale = std::sin(options.residual_scale_deg * kDegToRad);
  Eigen::Vector3d direction =
      ReweightedDirection(pair.normals, std::nullopt, scale, options.num_reweighting_rounds);
  // Enough wrong matches drag the unweighted first round so far that the rounds cannot come back
  // (a tenth of random matches already turns it far off); then the rounds restart from a sampled
  // start, and the direction more matches agree with stands. Off by default, and then not counted.
  const int agreeing =
      options.min_agreeing_share > 0.0 ? NumAgreeing(pair.normals, direction, scale) : 0;
  if (agreeing < options.min_agreeing_share * pair.normals.size()) {
    if (const auto start = SampledStart(pair.normals, scale, options.num_sampled_starts)) {
      const Eigen::Vector3d restarted =
          ReweightedDirection(pair.normals, start, scale, options.num_reweighting_rounds);
      if (NumAgreeing(pair.normals, restarted, scale) > agreeing) direction = restarted;
    }
  }
  if (!direction.allFinite()) return std::nullopt;
  const int sign = CheiralSign(pair, direction, scale, options);
  if (sign == 0) return std::nullopt;
  return static_cast<double>(sign) * (rotation1.conjugate() * direction.normalized());
}

}  // namespace ramap
