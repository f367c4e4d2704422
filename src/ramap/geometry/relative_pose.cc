#include "ramap/geometry/relative_pose.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <opengv/relative_pose/CentralRelativeAdapter.hpp>
#include <opengv/relative_pose/methods.hpp>
#include <opengv/sac/Ransac.hpp>
#include <opengv/sac_problems/relative_pose/CentralRelativePoseSacProblem.hpp>
#include <optional>
#include <sstream>

#include "ramap/geometry/epipolar_refinement.h"
#include "ramap/geometry/rotation.h"
#include "ramap/geometry/triangulation.h"
#include "ramap/util/error.h"
#include "ramap/util/even_subset.h"
#include "ramap/util/option_check.h"
#include "ramap/util/statistics.h"

namespace ramap {
namespace {

constexpr int kNumSamples = 6;

RelativePoseEstimate Reject(RelativePoseRejection rejection, const std::string& reason) {
  RelativePoseEstimate estimate;
  estimate.success = false;
  estimate.rejection = rejection;
  estimate.reason = reason;
  return estimate;
}

// The median (Median's element) of the angles between R a_k and b_k, unit vectors, over `indices`.
// The angle falls as the dot product grows, so it is the angle of the matching order statistic of
// the dot products: one arc tangent rather than one per match (the arc tangents of every match
// were a noticeable share of a long drive's relative poses).
double MedianAngle(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                   const Eigen::Matrix3d& R, const std::vector<int>& indices) {
  if (indices.empty()) return 0;
  std::vector<std::pair<double, int>> dots;
  dots.reserve(indices.size());
  for (const int k : indices) dots.emplace_back((R * a[k]).dot(b[k]), k);
  const auto mid = dots.begin() + static_cast<std::ptrdiff_t>(dots.size() / 2);
  std::nth_element(dots.begin(), mid, dots.end(), std::greater<>());
  return AngleBetween(R * a[mid->second], b[mid->second]);
}

bool IsRotation(const Eigen::Matrix3d& R) {
  return R.allFinite() && (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         R.determinant() > 0;
}

Eigen::Matrix3d Orthonormalize(const Eigen::Matrix3d& R) {
  return Eigen::Quaterniond(R).normalized().toRotationMatrix();
}

// Rotation R minimising sum |R f1 - f2|^2 (Kabsch / Arun): exact under pure rotation.
Eigen::Matrix3d FitPureRotation(const std::vector<Eigen::Vector3d>& f1,
                                const std::vector<Eigen::Vector3d>& f2,
                                const std::vector<int>& indices) {
  Eigen::Matrix3d cross_cov = Eigen::Matrix3d::Zero();
  for (int k : indices) cross_cov += f2[k] * f1[k].transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross_cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(2, 2) = -1;
  return svd.matrixU() * S * svd.matrixV().transpose();
}

// RMS angular distance (radians) of unit vectors to their best-fitting great circle.
double GreatCircleSpread(const std::vector<Eigen::Vector3d>& f) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& v : f) scatter += v * v.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter / static_cast<double>(f.size()));
  return std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
}

// Preemptive scoring of the rotation candidates (Nister, "Preemptive RANSAC for Live Structure and
// Motion Estimation", ICCV 2003), in two rounds: the five-point candidates (up to ~60 per pair) on
// an even subset of kNumFirstRoundMatches, the best kNumFirstRoundSurvivors of them together with
// the six-point eigensolver's (at most three) on kNumPreemptiveMatches. Against scoring every
// candidate on 200 matches: the same per-pair errors on the real sets, the mapper's results within
// the spread that moving the subset by one match gives, and a long drive's relative poses quicker
// (docs/benchmark-history.md, "Relative poses").
constexpr int kNumPreemptiveMatches = 200;
constexpr int kNumFirstRoundMatches = 50;
constexpr int kNumFirstRoundSurvivors = 3;

// Number of `indices` triangulating in front of both cameras under x2 = R x1 + t.
int CountInFront(const std::vector<Eigen::Vector3d>& f1, const std::vector<Eigen::Vector3d>& f2,
                 const std::vector<int>& indices, const Eigen::Matrix3d& R,
                 const Eigen::Vector3d& t) {
  int count = 0;
  for (int k : indices) {
    // d1 R f1 + t = d2 f2 in least squares; parallel rays have no depth.
    const std::optional<Eigen::Vector2d> depths = TwoRayDepths(R * f1[k], f2[k], -t);
    if (depths && (*depths)(0) > 0 && (*depths)(1) > 0) ++count;
  }
  return count;
}

struct Scored {
  double cost = std::numeric_limits<double>::infinity();
  std::vector<int> inliers;
  double inlier_sum_sq = 0;  // of the inliers' errors
};

// MSAC score of (R, t) over all matches.
Scored ScoreHypothesis(const std::vector<Eigen::Vector3d>& f1,
                       const std::vector<Eigen::Vector3d>& f2, const Eigen::Matrix3d& R,
                       const Eigen::Vector3d& t, double threshold) {
  Scored scored;
  scored.cost = 0;
  scored.inliers.reserve(f1.size());
  const double threshold_sq = threshold * threshold;
  for (size_t k = 0; k < f1.size(); ++k) {
    const double r = EpipolarError(R, t, f1[k], f2[k]);
    if (!(r < threshold)) {
      scored.cost += threshold_sq;
    } else {
      scored.cost += r * r;
      scored.inlier_sum_sq += r * r;
      scored.inliers.push_back(static_cast<int>(k));
    }
  }
  return scored;
}

// Scores R with t from its minimal support, then once more with t re-fitted on the inliers that
// found (a local-optimisation step as in LO-RANSAC: t from five or six noisy matches is poor).
Scored ScoreRotation(const std::vector<Eigen::Vector3d>& f1, const std::vector<Eigen::Vector3d>& f2,
                     const Eigen::Matrix3d& R, const Eigen::Vector3d& t_initial, double threshold,
                     Eigen::Vector3d* t) {
  Scored scored = ScoreHypothesis(f1, f2, R, t_initial, threshold);
  *t = t_initial;
  if (scored.inliers.size() >= 3) {
    const Eigen::Vector3d t_refit = TranslationFromRotation(f1, f2, scored.inliers, R);
    Scored rescored = ScoreHypothesis(f1, f2, R, t_refit, threshold);
    if (rescored.cost < scored.cost) {
      scored = std::move(rescored);
      *t = t_refit;
    }
  }
  return scored;
}

opengv::bearingVectors_t ToOpenGv(const std::vector<Eigen::Vector3d>& f) {
  return opengv::bearingVectors_t(f.begin(), f.end());
}

// A candidate rotation (cam2_from_cam1), the matches it was solved from and its translation
// direction (from the support, then re-fitted when the candidate is scored).
struct RotationCandidate {
  Eigen::Matrix3d R;
  std::vector<int> support;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// The rotation (camera 2 to camera 1, OpenGV's convention) of an essential matrix E with
// f1^T E f2 = 0, i.e. E = [t]x R. Of the two rotations E admits (R and R turned by 180 deg about t)
// one is returned: they have the same epipolar errors, so scoring cannot tell them apart, and
// ResolveCheirality chooses between them once the pose is refined.
Eigen::Matrix3d RotationOfEssential(const Eigen::Matrix3d& E) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU(), V = svd.matrixV();
  if (U.determinant() < 0) U = -U;
  if (V.determinant() < 0) V = -V;
  Eigen::Matrix3d W;
  W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  return U * W * V.transpose();
}

// Candidate rotations from the six selected matches. A five-point solver on five of the six (the
// other inliers disambiguate its roots), `leave_out` naming the one left out: Kneip's rotation-only
// solver or, with `nister_five_point`, Nister's essential matrices. With leave_out < 0, the
// eigensolver on all six started from the identity and from the six's pure-rotation fit (a good
// start under small baselines), and that fit itself. Trying every five of the six means that one
// bad match among the six still leaves a clean subset.
std::vector<RotationCandidate> RotationCandidatesFromSix(const std::vector<Eigen::Vector3d>& f1,
                                                         const std::vector<Eigen::Vector3d>& f2,
                                                         const std::vector<int>& six, int leave_out,
                                                         bool nister_five_point) {
  // The solvers see only the six (numbered 0-5 in the adapter): copying every bearing of the pair
  // into OpenGV's containers for each call cost more than the solvers.
  opengv::bearingVectors_t b1, b2;
  for (const int k : six) {
    b1.push_back(f1[k]);
    b2.push_back(f2[k]);
  }
  std::vector<RotationCandidate> candidates;
  auto add = [&](const opengv::rotation_t& R_2to1, const std::vector<int>& support) {
    if (!R_2to1.allFinite()) return;
    const Eigen::Matrix3d R = Orthonormalize(R_2to1.transpose());
    if (IsRotation(R))
      candidates.push_back({R, support, TranslationFromRotation(f1, f2, support, R)});
  };
  const int num_six = static_cast<int>(six.size());
  std::vector<int> local_six(num_six);
  for (int i = 0; i < num_six; ++i) local_six[i] = i;
  try {
    opengv::relative_pose::CentralRelativeAdapter adapter(b1, b2);
    if (leave_out >= 0) {
      std::vector<int> five, local_five;
      for (int i = 0; i < num_six; ++i) {
        if (i == leave_out) continue;
        five.push_back(six[i]);
        local_five.push_back(i);
      }
      if (nister_five_point) {
        for (const auto& E : opengv::relative_pose::fivept_nister(adapter, local_five)) {
          if (E.allFinite()) add(RotationOfEssential(E), five);
        }
      } else {
        for (const auto& R : opengv::relative_pose::fivept_kneip(adapter, local_five)) add(R, five);
      }
      return candidates;
    }
    add(opengv::relative_pose::eigensolver(adapter, local_six), six);
    const Eigen::Matrix3d R_rot = FitPureRotation(f1, f2, six);
    candidates.push_back({R_rot, six, TranslationFromRotation(f1, f2, six, R_rot)});
    opengv::relative_pose::CentralRelativeAdapter started(b1, b2, R_rot.transpose());
    add(opengv::relative_pose::eigensolver(started, local_six), six);
  } catch (const std::exception&) {
    // A solver failing on a degenerate sample leaves the candidates found so far.
  }
  return candidates;
}

// The bearings of some of a pair's matches, for preemptive scoring.
struct MatchSubset {
  std::vector<Eigen::Vector3d> f1, f2;
};

MatchSubset SubsetOf(const std::vector<Eigen::Vector3d>& f1, const std::vector<Eigen::Vector3d>& f2,
                     const std::vector<int>& indices) {
  MatchSubset subset;
  for (const int k : indices) {
    subset.f1.push_back(f1[k]);
    subset.f2.push_back(f2[k]);
  }
  return subset;
}

// A candidate with its MSAC cost, inlier count and inliers' RMS error on a subset.
struct ScoredCandidate {
  RotationCandidate candidate;
  double cost = std::numeric_limits<double>::infinity();
  int num_inliers = 0;
  double rms_inlier_error = std::numeric_limits<double>::infinity();
};

// When a five-point candidate ends the search (RelativePoseOptions::confident_inlier_ratio).
struct ConfidentCriterion {
  double min_inliers = std::numeric_limits<double>::infinity();
  double max_rms_error = 0;  // radians
};

bool IsConfident(const ScoredCandidate& scored, const ConfidentCriterion& criterion) {
  return scored.num_inliers >= criterion.min_inliers &&
         scored.rms_inlier_error <= criterion.max_rms_error;
}

// Scores `candidate` on `subset`, re-fitting its translation there (ScoreRotation).
ScoredCandidate ScoreCandidate(const MatchSubset& subset, double max_epipolar_error,
                               RotationCandidate candidate) {
  const Eigen::Vector3d t_start = candidate.t;
  const Scored scored =
      ScoreRotation(subset.f1, subset.f2, candidate.R, t_start, max_epipolar_error, &candidate.t);
  const int num_inliers = static_cast<int>(scored.inliers.size());
  const double rms_inlier_error = num_inliers > 0 ? std::sqrt(scored.inlier_sum_sq / num_inliers)
                                                  : std::numeric_limits<double>::infinity();
  return {std::move(candidate), scored.cost, num_inliers, rms_inlier_error};
}

// `scored` refined on its inliers among `subset` (a few steps) and scored again there; the better
// of the two.
ScoredCandidate RefinedOnSubset(const MatchSubset& subset, double max_epipolar_error,
                                const ScoredCandidate& scored) {
  const std::vector<int> inliers = ScoreHypothesis(subset.f1, subset.f2, scored.candidate.R,
                                                   scored.candidate.t, max_epipolar_error)
                                       .inliers;
  // Ten steps at loose tolerances: the test asks whether a good fit exists, not for its last digit.
  EpipolarRefinementOptions refinement;
  refinement.max_iterations = 10;
  refinement.function_tolerance = 1e-6;
  refinement.parameter_tolerance = 1e-8;
  RotationCandidate refined = scored.candidate;
  if (static_cast<int>(inliers.size()) < kNumSamples ||
      !RefineEpipolarPose(subset.f1, subset.f2, inliers, &refined.R, &refined.t, refinement)) {
    return scored;
  }
  ScoredCandidate rescored = ScoreCandidate(subset, max_epipolar_error, std::move(refined));
  return rescored.cost < scored.cost ? rescored : scored;
}

// How widely bearings spread: the RMS angle (radians) to their mean direction.
double BearingSpread(const std::vector<Eigen::Vector3d>& f) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : f) mean += v;
  if (f.empty() || mean.norm() < 1e-12) return M_PI;
  mean.normalize();
  double sum_sq = 0;
  for (const Eigen::Vector3d& v : f) {
    const double angle = AngleBetween(v, mean);
    sum_sq += angle * angle;
  }
  return std::sqrt(sum_sq / static_cast<double>(f.size()));
}

// The confident criterion of a pair (RelativePoseOptions::confident_inlier_ratio) on the first
// preemptive round's matches.
ConfidentCriterion ConfidentCriterionOf(const MatchSubset& first_round, int num_matches,
                                        double focal_length_px,
                                        const RelativePoseOptions& options) {
  ConfidentCriterion criterion;
  // A pair too weak to stop early needs more inliers than any candidate can have.
  if (num_matches >= options.confident_min_matches) {
    criterion.min_inliers =
        options.confident_inlier_ratio * static_cast<double>(first_round.f1.size());
  }
  const bool narrow = BearingSpread(first_round.f1) < options.confident_narrow_view_deg * kDegToRad;
  criterion.max_rms_error =
      (narrow ? options.confident_narrow_view_rms_error_px : options.confident_max_rms_error_px) /
      focal_length_px;
  return criterion;
}

// The `count` candidates of lowest cost, best first.
std::vector<RotationCandidate> BestScored(std::vector<ScoredCandidate> scored, int count) {
  std::vector<std::pair<double, size_t>> ranked;
  for (size_t c = 0; c < scored.size(); ++c) {
    if (std::isfinite(scored[c].cost)) ranked.emplace_back(scored[c].cost, c);
  }
  const size_t kept = std::min(ranked.size(), static_cast<size_t>(count));
  std::partial_sort(ranked.begin(), ranked.begin() + kept, ranked.end());
  std::vector<RotationCandidate> best;
  for (size_t r = 0; r < kept; ++r) best.push_back(std::move(scored[ranked[r].second].candidate));
  return best;
}

// The RANSAC baseline: OpenGV's central relative pose problem with Nister's five-point solver.
bool RansacFivePoint(const std::vector<Eigen::Vector3d>& f1, const std::vector<Eigen::Vector3d>& f2,
                     const RelativePoseOptions& options, double max_epipolar_error,
                     Eigen::Matrix3d* R, Eigen::Vector3d* t) {
  using Problem = opengv::sac_problems::relative_pose::CentralRelativePoseSacProblem;
  const opengv::bearingVectors_t b1 = ToOpenGv(f1), b2 = ToOpenGv(f2);
  try {
    opengv::relative_pose::CentralRelativeAdapter adapter(b1, b2);
    opengv::sac::Ransac<Problem> ransac;
    // OpenGV seeds its own generator (fixed when randomSeed is false); options.seed is unused.
    ransac.sac_model_ = std::make_shared<Problem>(adapter, Problem::NISTER, false);
    // OpenGV's score is the sum over both views of 1 - cos(reprojection angle).
    ransac.threshold_ = 2.0 * (1.0 - std::cos(max_epipolar_error));
    ransac.max_iterations_ = options.ransac_max_iterations;
    ransac.probability_ = options.ransac_probability;
    if (!ransac.computeModel()) return false;
    // OpenGV's model: x1 = R_2to1 x2 + t_2in1, so cam2_from_cam1 = (R_2to1^T, -R_2to1^T t_2in1).
    const Eigen::Matrix3d R_2to1 = ransac.model_coefficients_.leftCols<3>();
    const Eigen::Vector3d t_2in1 = ransac.model_coefficients_.col(3);
    if (!R_2to1.allFinite() || !t_2in1.allFinite() || t_2in1.norm() < 1e-12) return false;
    *R = Orthonormalize(R_2to1.transpose());
    *t = -(R_2to1.transpose() * t_2in1).normalized();
    return IsRotation(*R);
  } catch (const std::exception&) {
    return false;
  }
}

std::string Percent(double ratio) {
  std::ostringstream out;
  out.precision(3);
  out << 100.0 * ratio << "%";
  return out.str();
}

}  // namespace

void RelativePoseOptions::Check() const {
  CheckOptionValues(RelativePoseOptionTable(), *this);
  // The settings no command line option reaches.
  const std::string s = "RelativePoseOptions::";
  CheckOption(min_cell_distance >= 1, s + "min_cell_distance", ">= 1", min_cell_distance);
  CheckOption(min_inlier_ratio >= 0 && min_inlier_ratio <= 1, s + "min_inlier_ratio", "in [0, 1]",
              min_inlier_ratio);
  CheckOption(min_motion_deg >= 0, s + "min_motion_deg", ">= 0", min_motion_deg);
  CheckOption(min_bearing_spread >= 0, s + "min_bearing_spread", ">= 0", min_bearing_spread);
  CheckOption(max_refinement_matches >= kNumSamples, s + "max_refinement_matches", ">= 6",
              max_refinement_matches);
  CheckOption(ransac_max_iterations >= 1, s + "ransac_max_iterations", ">= 1",
              ransac_max_iterations);
  CheckOption(ransac_probability > 0 && ransac_probability < 1, s + "ransac_probability",
              "in (0, 1)", ransac_probability);
}

namespace {

// asin(s) for s in [0, 1]. Epipolar errors are mostly below 0.01 rad, where four terms of the
// series s + s^3/6 + 3 s^5/40 + 15 s^7/336 are exact to double precision (the next term is below
// 1e-17 of s) and cost a fraction of the library call, which was a noticeable share of the
// mapper's time on long drives.
double SmallAsin(double s) {
  if (s >= 0.01) return std::asin(s);
  const double s2 = s * s;
  return s * (1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (15.0 / 336.0))));
}

}  // namespace

double EpipolarError(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Vector3d& f1,
                     const Eigen::Vector3d& f2) {
  const Eigen::Vector3d rf1 = R * f1;
  const double algebraic = std::abs(t.dot(rf1.cross(f2)));
  // The plane through the baseline and R f1 has normal t x R f1; its sine distance to f2 is the
  // algebraic error over |t x R f1| (and symmetrically for f1 with |t x f2|).
  const double d1 = std::max(t.cross(rf1).norm(), 1e-12);
  const double d2 = std::max(t.cross(f2).norm(), 1e-12);
  const double s2 = std::min(1.0, algebraic / d1), s1 = std::min(1.0, algebraic / d2);
  return 0.5 * (SmallAsin(s1) + SmallAsin(s2));
}

Eigen::Vector3d TranslationFromRotation(const std::vector<Eigen::Vector3d>& bearings1,
                                        const std::vector<Eigen::Vector3d>& bearings2,
                                        const std::vector<int>& indices, const Eigen::Matrix3d& R,
                                        double* min_eigenvalue) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (int k : indices) {
    const Eigen::Vector3d n = (R * bearings1[k]).cross(bearings2[k]);
    M += n * n.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
  if (min_eigenvalue != nullptr) *min_eigenvalue = eig.eigenvalues()(0);
  return eig.eigenvectors().col(0).normalized();
}

namespace {

using Bearings = std::vector<Eigen::Vector3d>;
using Rejection = RelativePoseRejection;

// The pixel thresholds as angles (small-angle: an angle times the focal length is pixels).
struct AngularThresholds {
  double max_epipolar_error = 0;
  double pure_rotation_parallax = 0;
};

// The checks on the input that need no geometry: lengths, counts, sizes, the focal length.
std::optional<RelativePoseEstimate> InputRejection(const TwoViewCorrespondences& matches,
                                                   const RelativePoseOptions& options) {
  const size_t n = matches.size();
  if (matches.bearings2.size() != n || matches.pixels1.size() != n || matches.pixels2.size() != n ||
      (!matches.confidence.empty() && matches.confidence.size() != n)) {
    return Reject(Rejection::kInvalidInput,
                  "inconsistent input: bearings, pixels and confidences differ in length");
  }
  if (static_cast<int>(n) < std::max(kNumSamples, options.min_num_inliers)) {
    return Reject(Rejection::kTooFewMatches,
                  "only " + std::to_string(n) + " matches, need at least " +
                      std::to_string(std::max(kNumSamples, options.min_num_inliers)));
  }
  if (matches.width1 <= 0 || matches.height1 <= 0 || matches.width2 <= 0 || matches.height2 <= 0) {
    return Reject(Rejection::kInvalidInput, "image sizes must be positive");
  }
  if (!(matches.focal_length_px > 0) || !std::isfinite(matches.focal_length_px)) {
    return Reject(Rejection::kUnknownFocalLength,
                  "focal length unknown: pixel thresholds cannot be turned into angles");
  }
  return std::nullopt;
}

// The unit bearings of both images into f1, f2; a rejection on a non-finite value or zero bearing.
std::optional<RelativePoseEstimate> UnitBearings(const TwoViewCorrespondences& matches,
                                                 Bearings* f1, Bearings* f2) {
  const size_t n = matches.size();
  f1->resize(n);
  f2->resize(n);
  for (size_t k = 0; k < n; ++k) {
    const bool finite = matches.bearings1[k].allFinite() && matches.bearings2[k].allFinite() &&
                        matches.pixels1[k].allFinite() && matches.pixels2[k].allFinite() &&
                        (matches.confidence.empty() || std::isfinite(matches.confidence[k]));
    if (!finite)
      return Reject(Rejection::kInvalidInput, "non-finite value in match " + std::to_string(k));
    if (matches.bearings1[k].norm() < 1e-12 || matches.bearings2[k].norm() < 1e-12) {
      return Reject(Rejection::kInvalidInput, "zero bearing vector in match " + std::to_string(k));
    }
    (*f1)[k] = matches.bearings1[k].normalized();
    (*f2)[k] = matches.bearings2[k].normalized();
  }
  return std::nullopt;
}

// Spread: one grid cell, or bearings on one great circle (keypoints on one image line), leave
// the rotation undetermined. Motion: identical views have none.
std::optional<RelativePoseEstimate> SpreadOrMotionRejection(const TwoViewCorrespondences& matches,
                                                            const Bearings& f1, const Bearings& f2,
                                                            const std::vector<int>& all,
                                                            const RelativePoseOptions& options) {
  const size_t n = matches.size();
  const ImageGrid grid1{options.grid_cols, options.grid_rows, matches.width1, matches.height1};
  const ImageGrid grid2{options.grid_cols, options.grid_rows, matches.width2, matches.height2};
  std::vector<bool> occupied1(options.grid_cols * options.grid_rows, false);
  std::vector<bool> occupied2(occupied1.size(), false);
  for (size_t k = 0; k < n; ++k) {
    occupied1[grid1.CellIndex(matches.pixels1[k])] = true;
    occupied2[grid2.CellIndex(matches.pixels2[k])] = true;
  }
  if (std::count(occupied1.begin(), occupied1.end(), true) < 2 ||
      std::count(occupied2.begin(), occupied2.end(), true) < 2) {
    return Reject(Rejection::kTooLittleSpread,
                  "all matches fall into one grid cell: too little spread");
  }
  if (GreatCircleSpread(f1) < options.min_bearing_spread ||
      GreatCircleSpread(f2) < options.min_bearing_spread) {
    return Reject(Rejection::kTooLittleSpread,
                  "matches are collinear in an image: rotation undetermined");
  }
  if (MedianAngle(f1, f2, Eigen::Matrix3d::Identity(), all) < options.min_motion_deg * kDegToRad) {
    return Reject(Rejection::kNoMotion,
                  "no motion between the images (identical or duplicate views)");
  }
  return std::nullopt;
}

// Pure rotation / low parallax: the epipolar constraint is then satisfied by any translation and
// the solvers are ill-posed, so it is tested first with a pure-rotation fit, refit once on the
// matches it explains. Returns the pure-rotation estimate (or its rejection); nothing when the
// pair has parallax.
std::optional<RelativePoseEstimate> PureRotationOutcome(const Bearings& f1, const Bearings& f2,
                                                        const std::vector<int>& all,
                                                        const AngularThresholds& thresholds,
                                                        const RelativePoseOptions& options) {
  Eigen::Matrix3d R = FitPureRotation(f1, f2, all);
  if (!(MedianAngle(f1, f2, R, all) < thresholds.pure_rotation_parallax)) return std::nullopt;
  std::vector<int> inliers;
  const double inlier_threshold =
      std::max(2.0 * thresholds.pure_rotation_parallax, thresholds.max_epipolar_error);
  for (const int k : all) {
    if (AngleBetween(R * f1[k], f2[k]) < inlier_threshold) inliers.push_back(k);
  }
  if (static_cast<int>(inliers.size()) < options.min_num_inliers) {
    return Reject(Rejection::kPureRotationTooFewInliers,
                  "pure rotation with only " + std::to_string(inliers.size()) + " inliers");
  }
  R = FitPureRotation(f1, f2, inliers);
  RelativePoseEstimate estimate;
  estimate.success = true;
  estimate.rotation = Eigen::Quaterniond(R).normalized();
  estimate.translation.setZero();
  estimate.inliers = inliers;
  estimate.num_inliers = static_cast<int>(inliers.size());
  estimate.median_residual = MedianAngle(f1, f2, R, inliers);
  estimate.median_parallax_deg = estimate.median_residual * kRadToDeg;
  estimate.cheirality_ratio = 1.0;
  estimate.flags = kRelativePosePureRotation;
  return estimate;
}

// The paper's hypothesis: six grid-selected (or random, or ROI) correspondences, the rotation
// candidates of the five-point solver on each five of them until one is confident
// (RelativePoseOptions::confident_inlier_ratio), and of the six-point solver on all six when none
// was, ranked by the two rounds of preemptive scoring
// described at kNumPreemptiveMatches (only the best is then scored on all matches). A rejection
// when no six could be selected or no solver returned a rotation. Counts the five-point subsets
// solved.
std::optional<RelativePoseEstimate> SixPointHypothesis(
    const TwoViewCorrespondences& matches, const Bearings& f1, const Bearings& f2,
    const std::vector<int>& all, const RelativePoseOptions& options, double max_epipolar_error,
    Eigen::Matrix3d* R, Eigen::Vector3d* t, int* num_five_point_subsets) {
  std::vector<int> six;
  switch (options.sampler) {
    case CorrespondenceSampler::kGrid:
      six = SelectGridCorrespondences(matches, options.grid_cols, options.grid_rows, kNumSamples,
                                      options.min_cell_distance);
      break;
    case CorrespondenceSampler::kRandom:
      six = SelectRandomCorrespondences(matches, kNumSamples, options.seed);
      break;
    case CorrespondenceSampler::kRoi:
      six = SelectRoiCorrespondences(matches, options.grid_cols, options.grid_rows, kNumSamples);
      break;
    case CorrespondenceSampler::kRansac5:
      break;
  }
  if (static_cast<int>(six.size()) < kNumSamples) {
    return Reject(Rejection::kNoHypothesis, "could not select six correspondences");
  }
  const MatchSubset first_round = SubsetOf(f1, f2, EvenSubset(all, kNumFirstRoundMatches));
  const ConfidentCriterion confident_criterion = ConfidentCriterionOf(
      first_round, static_cast<int>(all.size()), matches.focal_length_px, options);
  bool confident = false;
  std::vector<ScoredCandidate> five_point_candidates;
  for (int leave_out = 0; leave_out < kNumSamples && !confident; ++leave_out) {
    ++*num_five_point_subsets;
    for (RotationCandidate& candidate :
         RotationCandidatesFromSix(f1, f2, six, leave_out, options.nister_five_point)) {
      ScoredCandidate scored =
          ScoreCandidate(first_round, max_epipolar_error, std::move(candidate));
      if (scored.num_inliers >= confident_criterion.min_inliers &&
          !IsConfident(scored, confident_criterion)) {
        scored = RefinedOnSubset(first_round, max_epipolar_error, scored);
      }
      confident |= IsConfident(scored, confident_criterion);
      five_point_candidates.push_back(std::move(scored));
    }
  }
  // A confident five-point candidate makes the all-six eigensolver's starts (a good share of a
  // pair's time) redundant: every real set's pair errors and a synthetic drive's are the same
  // without them (docs/benchmark-history.md, "Relative poses").
  std::vector<RotationCandidate> candidates;
  if (!confident)
    candidates = RotationCandidatesFromSix(f1, f2, six, -1, options.nister_five_point);
  for (RotationCandidate& candidate :
       BestScored(std::move(five_point_candidates), kNumFirstRoundSurvivors)) {
    candidates.push_back(std::move(candidate));
  }
  const MatchSubset second_round = SubsetOf(f1, f2, EvenSubset(all, kNumPreemptiveMatches));
  std::vector<ScoredCandidate> finalists;
  for (RotationCandidate& candidate : candidates) {
    finalists.push_back(ScoreCandidate(second_round, max_epipolar_error, std::move(candidate)));
  }
  const std::vector<RotationCandidate> best = BestScored(std::move(finalists), 1);
  if (best.empty()) {
    return Reject(Rejection::kNoHypothesis, "the six-point solvers returned no rotation");
  }
  *R = best.front().R;
  *t = best.front().t;
  return std::nullopt;
}

// The best hypothesis (the paper's six-point rotation, or the RANSAC baseline) scored on every
// match: its rotation, translation and inliers; a rejection when there is none or it explains
// fewer than six matches.
std::optional<RelativePoseEstimate> BestHypothesis(const TwoViewCorrespondences& matches,
                                                   const Bearings& f1, const Bearings& f2,
                                                   const std::vector<int>& all,
                                                   const RelativePoseOptions& options,
                                                   double max_epipolar_error, Eigen::Matrix3d* R,
                                                   Eigen::Vector3d* t, std::vector<int>* inliers,
                                                   int* num_five_point_subsets) {
  Scored best;
  if (options.sampler == CorrespondenceSampler::kRansac5) {
    Eigen::Vector3d t_ransac;
    if (!RansacFivePoint(f1, f2, options, max_epipolar_error, R, &t_ransac)) {
      return Reject(Rejection::kNoHypothesis, "RANSAC five-point found no essential matrix");
    }
    best = ScoreRotation(f1, f2, *R, t_ransac, max_epipolar_error, t);
  } else {
    if (auto rejected = SixPointHypothesis(matches, f1, f2, all, options, max_epipolar_error, R, t,
                                           num_five_point_subsets)) {
      return rejected;
    }
    best = ScoreRotation(f1, f2, *R, *t, max_epipolar_error, t);
  }
  if (static_cast<int>(best.inliers.size()) < kNumSamples) {
    return Reject(Rejection::kTooFewInliers,
                  "rotation inconsistent with the epipolar constraint: only " +
                      std::to_string(best.inliers.size()) + " inliers");
  }
  *inliers = best.inliers;
  return std::nullopt;
}

// Refines on all inliers, drops the matches the refined model does not explain and refits, until
// the inlier set is stable (a few rounds at most), so that the estimate is a fit of its final
// inliers only.
std::optional<RelativePoseEstimate> RefineUntilStable(const Bearings& f1, const Bearings& f2,
                                                      const RelativePoseOptions& options,
                                                      double max_epipolar_error,
                                                      std::vector<int>* inliers, Eigen::Matrix3d* R,
                                                      Eigen::Vector3d* t) {
  constexpr int kMaxRefineRounds = 4;
  for (int round = 0;; ++round) {
    if (!RefineEpipolarPose(f1, f2, EvenSubset(*inliers, options.max_refinement_matches), R, t)) {
      return Reject(Rejection::kRefinementDiverged, "refinement diverged");
    }
    if (round + 1 == kMaxRefineRounds) break;
    std::vector<int> rescored = ScoreHypothesis(f1, f2, *R, *t, max_epipolar_error).inliers;
    if (static_cast<int>(rescored.size()) < options.min_num_inliers) {
      return Reject(Rejection::kTooFewInliers,
                    "only " + std::to_string(rescored.size()) + " inliers after refinement");
    }
    if (rescored == *inliers) break;
    *inliers = std::move(rescored);
  }
  return std::nullopt;
}

// The translation direction from the rotation, then the four-fold (R, +-t, twisted R) ambiguity
// of the epipolar constraint resolved by cheirality. Returns how many inliers are in front.
int ResolveCheirality(const Bearings& f1, const Bearings& f2, const std::vector<int>& inliers,
                      Eigen::Matrix3d* R, Eigen::Vector3d* t) {
  *t = TranslationFromRotation(f1, f2, inliers, *R);
  const Eigen::Matrix3d R_refined = *R;
  const Eigen::Matrix3d R_twisted = Eigen::AngleAxisd(M_PI, *t).toRotationMatrix() * *R;
  const Eigen::Vector3d t_refined = *t;
  int best_in_front = -1;
  for (const Eigen::Matrix3d* R_option : {&R_refined, &R_twisted}) {
    for (double sign : {1.0, -1.0}) {
      const int in_front = CountInFront(f1, f2, inliers, *R_option, sign * t_refined);
      if (in_front > best_in_front) {
        best_in_front = in_front;
        *R = *R_option;
        *t = sign * t_refined;
      }
    }
  }
  return best_in_front;
}

// The accepted estimate of (R, t) on `inliers`, with its residuals and parallax; pure rotation
// when the parallax is below the threshold after all.
RelativePoseEstimate FinalEstimate(const Bearings& f1, const Bearings& f2,
                                   const std::vector<int>& inliers, const Eigen::Matrix3d& R,
                                   const Eigen::Vector3d& t, int num_in_front,
                                   const AngularThresholds& thresholds) {
  RelativePoseEstimate estimate;
  estimate.success = true;
  estimate.rotation = Eigen::Quaterniond(R).normalized();
  estimate.translation = t;
  estimate.inliers = inliers;
  estimate.num_inliers = static_cast<int>(inliers.size());
  std::vector<double> residuals;
  for (int k : inliers) residuals.push_back(EpipolarError(R, t, f1[k], f2[k]));
  const double median_parallax = MedianAngle(f1, f2, R, inliers);
  estimate.median_residual = residuals.empty() ? 0.0 : Median(residuals);
  estimate.median_parallax_deg = median_parallax * kRadToDeg;
  estimate.cheirality_ratio = static_cast<double>(num_in_front) / inliers.size();
  if (median_parallax < thresholds.pure_rotation_parallax) {
    estimate.flags |= kRelativePosePureRotation;
    estimate.translation.setZero();
  }
  if (!estimate.rotation.coeffs().allFinite() || !estimate.translation.allFinite()) {
    return Reject(Rejection::kNonFiniteEstimate, "non-finite estimate");
  }
  return estimate;
}

}  // namespace

RelativePoseEstimate EstimateRelativePose(const TwoViewCorrespondences& matches,
                                          const RelativePoseOptions& options) {
  if (auto rejected = InputRejection(matches, options)) return *rejected;
  const AngularThresholds thresholds{options.max_epipolar_error_px / matches.focal_length_px,
                                     options.pure_rotation_parallax_px / matches.focal_length_px};
  Bearings f1, f2;
  if (auto rejected = UnitBearings(matches, &f1, &f2)) return *rejected;
  std::vector<int> all(matches.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  if (auto rejected = SpreadOrMotionRejection(matches, f1, f2, all, options)) return *rejected;
  if (auto pure = PureRotationOutcome(f1, f2, all, thresholds, options)) return *pure;

  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  std::vector<int> inliers;
  int num_five_point_subsets = 0;
  if (auto rejected = BestHypothesis(matches, f1, f2, all, options, thresholds.max_epipolar_error,
                                     &R, &t, &inliers, &num_five_point_subsets)) {
    return *rejected;
  }
  if (auto rejected =
          RefineUntilStable(f1, f2, options, thresholds.max_epipolar_error, &inliers, &R, &t)) {
    return *rejected;
  }
  // The paper's consistency check: the rotation must explain most of the verified matches.
  const double ratio = static_cast<double>(inliers.size()) / static_cast<double>(matches.size());
  if (ratio < options.min_inlier_ratio) {
    return Reject(Rejection::kLowInlierRatio,
                  "rotation inconsistent with the epipolar constraint: only " + Percent(ratio) +
                      " of the matches are inliers");
  }
  const int num_in_front = ResolveCheirality(f1, f2, inliers, &R, &t);
  RelativePoseEstimate estimate = FinalEstimate(f1, f2, inliers, R, t, num_in_front, thresholds);
  estimate.num_five_point_subsets = num_five_point_subsets;
  return estimate;
}

}  // namespace ramap
