#include "ramap/estimators/view_graph_calibration.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "ramap/geometry/camera_distortion.h"
#include "ramap/geometry/camera_projection.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/statistics.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

struct FundamentalPair {
  uint32_t camera1 = 0;
  uint32_t camera2 = 0;
  Eigen::Matrix3d F;
  int num_inliers = 0;
};

// Pairs whose stored F is meaningful: verified as a general two-view geometry (pure rotations and
// planes leave F undetermined), finite and non-zero, with enough inliers.
std::vector<FundamentalPair> PairsWithFundamentalMatrix(const FeatureDatabase& database,
                                                        int min_num_inliers) {
  std::vector<FundamentalPair> pairs;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (geometry.config != TwoViewConfig::kCalibrated &&
        geometry.config != TwoViewConfig::kUncalibrated) {
      continue;
    }
    if (static_cast<int>(geometry.inlier_matches.size()) < min_num_inliers) continue;
    const double norm = geometry.F.norm();
    if (!geometry.F.allFinite() || !(norm > 0)) continue;
    const auto image1 = database.images.find(geometry.image_id1);
    const auto image2 = database.images.find(geometry.image_id2);
    if (image1 == database.images.end() || image2 == database.images.end()) continue;
    pairs.push_back({image1->second.camera_id, image2->second.camera_id, geometry.F / norm,
                     static_cast<int>(geometry.inlier_matches.size())});
  }
  return pairs;
}

double CauchyLoss(double cost, double scale) {
  const double r = cost / scale;
  return std::log1p(r * r);
}

// The terms of one camera's cost: the pairs that see it.
struct CameraTerms {
  std::vector<const FundamentalPair*> pairs;
};

class FocalCost {
 public:
  FocalCost(const std::map<uint32_t, Camera>& cameras, const ViewGraphCalibrationOptions& options,
            std::map<uint32_t, double>* log_scales)
      : cameras_(cameras), options_(options), log_scales_(*log_scales) {}

  double PairCost(const FundamentalPair& pair) const {
    return EssentialMatrixCost(pair.F, K(pair.camera1), K(pair.camera2));
  }

  // Robust sum over `terms` plus the prior, with camera `camera_id` at log scale `log_scale`.
  double Evaluate(uint32_t camera_id, const CameraTerms& terms, double log_scale) {
    const double prior = log_scale / std::log(2.0);
    return PairsCost(camera_id, terms, log_scale) + options_.prior_weight * prior * prior;
  }

  // The robust sum over `terms` alone.
  double PairsCost(uint32_t camera_id, const CameraTerms& terms, double log_scale) {
    log_scales_[camera_id] = log_scale;
    double total = 0.0;
    for (const FundamentalPair* pair : terms.pairs) {
      total += CauchyLoss(PairCost(*pair), options_.loss_scale);
    }
    return total;
  }

  // The same with every camera of `offsets` at log scale offset + `log_ratio` (one common
  // focal length over the longest side when the offsets are each camera's log(longest side /
  // prior)), over `pairs`.
  double EvaluateCommon(const std::map<uint32_t, double>& offsets,
                        const std::vector<const FundamentalPair*>& pairs, double log_ratio) {
    double prior_term = 0.0;
    for (const auto& [camera_id, offset] : offsets) {
      log_scales_[camera_id] = offset + log_ratio;
      const double prior = (offset + log_ratio) / std::log(2.0);
      prior_term += options_.prior_weight * prior * prior;
    }
    double total = 0.0;
    for (const FundamentalPair* pair : pairs) {
      total += CauchyLoss(PairCost(*pair), options_.loss_scale);
    }
    return total + prior_term;
  }

  double loss_scale() const { return options_.loss_scale; }

 private:
  Eigen::Matrix3d K(uint32_t camera_id) const {
    const auto scale = log_scales_.find(camera_id);
    return CalibrationMatrix(cameras_.at(camera_id),
                             scale == log_scales_.end() ? 1.0 : std::exp(scale->second));
  }

  const std::map<uint32_t, Camera>& cameras_;
  const ViewGraphCalibrationOptions& options_;
  std::map<uint32_t, double>& log_scales_;
};

// Minimises `cost(log_scale)` over [low, high]: a grid, then golden-section search around its
// best sample. Returns the minimiser and, in `at_edge`, whether it sits on the range's boundary.
// The grid's step is 1.2% of the focal length, fine enough that golden-section search starts in
// the minimum's own valley.
constexpr double kGridStep = 0.01155;  // ln(16) / 240

template <typename Cost>
double MinimiseOverLogScale(Cost&& cost, double low, double high, bool* at_edge) {
  const int kSamples = std::max(3, static_cast<int>(std::ceil((high - low) / kGridStep)) + 1);
  const double step = (high - low) / (kSamples - 1);
  int best = 0;
  double best_cost = cost(low);
  for (int k = 1; k < kSamples; ++k) {
    const double value = cost(low + k * step);
    if (value < best_cost) {
      best_cost = value;
      best = k;
    }
  }
  *at_edge = best == 0 || best == kSamples - 1;
  double a = low + std::max(0, best - 1) * step;
  double b = low + std::min(kSamples - 1, best + 1) * step;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - ratio * (b - a), d = a + ratio * (b - a);
  double fc = cost(c), fd = cost(d);
  for (int iteration = 0; iteration < 40; ++iteration) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - ratio * (b - a);
      fc = cost(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + ratio * (b - a);
      fd = cost(d);
    }
  }
  const double refined = 0.5 * (a + b);
  return cost(refined) <= best_cost ? refined : low + best * step;
}

}  // namespace

void ViewGraphCalibrationOptions::Check() const {
  CheckOptionValues(ViewGraphCalibrationOptionTable(), *this);
  // The settings no command line option reaches.
  const std::string s = "ViewGraphCalibrationOptions::";
  CheckOption(min_focal_ratio > 0, s + "min_focal_ratio", "> 0", min_focal_ratio);
  CheckOption(max_focal_ratio > min_focal_ratio && std::isfinite(max_focal_ratio),
              s + "max_focal_ratio", "finite and > min_focal_ratio", max_focal_ratio);
  CheckOption(min_num_inliers >= 8, s + "min_num_inliers", ">= 8", min_num_inliers);
  CheckOption(max_pairs_per_camera >= 1, s + "max_pairs_per_camera", ">= 1", max_pairs_per_camera);
  CheckOption(loss_scale > 0, s + "loss_scale", "> 0", loss_scale);
  CheckOption(prior_weight >= 0, s + "prior_weight", ">= 0", prior_weight);
  CheckOption(num_rounds >= 1, s + "num_rounds", ">= 1", num_rounds);
  CheckOption(round_search_factor >= 1, s + "round_search_factor", ">= 1", round_search_factor);
  CheckOption(min_cost_rise >= 0, s + "min_cost_rise", ">= 0", min_cost_rise);
}

double EssentialMatrixCost(const Eigen::Matrix3d& F, const Eigen::Matrix3d& K1,
                           const Eigen::Matrix3d& K2) {
  // The singular values from the eigenvalues of M^T M, in closed form: the search evaluates this
  // hundreds of times per pair, and an iterative SVD was most of its time.
  const Eigen::Matrix3d M = K2.transpose() * F * K1;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(M.transpose() * M, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d& ascending = eigen.eigenvalues();
  const double s1 = std::sqrt(std::max(ascending[2], 0.0));
  const double s2 = std::sqrt(std::max(ascending[1], 0.0));
  if (!(s1 > 0) || !std::isfinite(s1)) return 1.0;
  return (s1 - s2) / (s1 + s2);
}

namespace {

// The cameras the view graph estimates: those the database marks unknown (prior_focal_length 0)
// and, with test_given_focal_lengths, those it gives a focal length; fisheye models aside. Maps
// each to whether its focal length is given.
std::map<uint32_t, bool> CamerasToEstimate(const FeatureDatabase& database,
                                           const std::map<uint32_t, Camera>& cameras,
                                           const ViewGraphCalibrationOptions& options) {
  std::map<uint32_t, bool> to_estimate;
  for (const auto& [camera_id, camera] : cameras) {
    const auto stored = database.cameras.find(camera_id);
    if (stored == database.cameras.end() || IsFisheyeModel(camera.model)) continue;
    const bool given = stored->second.has_prior_focal_length;
    if (!given || options.test_given_focal_lengths) to_estimate[camera_id] = given;
  }
  return to_estimate;
}

// The pairs of each camera to estimate, at most max_pairs_per_camera (those with the most
// inliers).
std::map<uint32_t, CameraTerms> TermsOfCameras(const std::vector<FundamentalPair>& pairs,
                                               const std::map<uint32_t, bool>& to_estimate,
                                               const std::map<uint32_t, Camera>& cameras,
                                               const ViewGraphCalibrationOptions& options) {
  std::map<uint32_t, CameraTerms> terms;
  for (const FundamentalPair& pair : pairs) {
    if (!cameras.count(pair.camera1) || !cameras.count(pair.camera2)) continue;
    for (const uint32_t id : {pair.camera1, pair.camera2}) {
      if (to_estimate.count(id)) terms[id].pairs.push_back(&pair);
      if (pair.camera1 == pair.camera2) break;
    }
  }
  for (auto& [camera_id, camera_terms] : terms) {
    std::vector<const FundamentalPair*>& camera_pairs = camera_terms.pairs;
    if (static_cast<int>(camera_pairs.size()) <= options.max_pairs_per_camera) continue;
    std::stable_sort(camera_pairs.begin(), camera_pairs.end(),
                     [](const FundamentalPair* a, const FundamentalPair* b) {
                       return a->num_inliers > b->num_inliers;
                     });
    camera_pairs.resize(options.max_pairs_per_camera);
  }
  return terms;
}

// How a camera's cost behaves at its estimate (the estimate itself is in the cost's log scales).
// How well the pairs alone (the prior's curvature aside) fix a camera's focal length: the rise
// of their cost 20% below and 25% above the minimum, relative to the minimum. The minimum is
// floored at a per-pair cost of 0.002 (a small fraction of what noisy matches leave), so that
// pairs that fit every focal length exactly (a noise-free turntable) count as flat, not as an
// infinite rise over zero.
double CostRise(FocalCost* cost, uint32_t camera_id, const CameraTerms& terms, double best) {
  auto at = [&](double log_scale) { return cost->PairsCost(camera_id, terms, log_scale); };
  const double floor = terms.pairs.size() * CauchyLoss(0.002, cost->loss_scale());
  const double minimum = std::max(at(best), floor);
  const double rise = std::min(at(best + std::log(0.8)), at(best + std::log(1.25))) - minimum;
  at(best);  // leave the camera at its minimum
  return rise / minimum;
}

struct EstimateShape {
  bool at_edge = false;    // the minimum sits on the search range's boundary
  double cost_rise = 0.0;  // CostRise
};

// A camera's search range in log scales of its prior: the absolute focal-length ratios of the
// options over its longest side.
struct LogRange {
  double low = 0.0;
  double high = 0.0;
};

LogRange SearchRange(const Camera& camera, const ViewGraphCalibrationOptions& options) {
  const double prior = MeanFocalLength(camera);
  const double longest = static_cast<double>(std::max(camera.width, camera.height));
  // A camera without a size (never from COLMAP) is searched around its prior as if it were
  // COLMAP's guess, 1.2 x the longest side.
  const double side = longest > 0 ? longest : prior / 1.2;
  return {std::log(options.min_focal_ratio * side / prior),
          std::log(options.max_focal_ratio * side / prior)};
}

// Where a camera's rounds search: its whole range when it has no start yet (it is estimated
// alone), else within a factor of 3 of its start. With a camera per image, each has a few pairs,
// and over the whole range one camera alone found minima at 3-4 times its focal length (pairs
// whose F is nearly affine fit a long focal length about as well), which the next cameras then
// followed; the common start is within that factor of the truth on every set here.
LogRange RoundRange(const LogRange& range, const std::map<uint32_t, double>& log_scales,
                    uint32_t camera_id, const ViewGraphCalibrationOptions& options) {
  const auto start = log_scales.find(camera_id);
  if (start == log_scales.end() || !(options.round_search_factor > 1)) return range;
  const double window = std::log(options.round_search_factor);
  return {std::max(range.low, start->second - window),
          std::min(range.high, start->second + window)};
}

// Minimises the cost over the log scales of the cameras in `estimable` (each with at least
// min_num_pairs pairs): first one common factor for the unknown ones, then camera by camera, each
// over its own range.
std::map<uint32_t, EstimateShape> EstimateLogScales(
    const std::map<uint32_t, const CameraTerms*>& estimable, const std::map<uint32_t, bool>& given,
    const std::map<uint32_t, LogRange>& ranges, const ViewGraphCalibrationOptions& options,
    FocalCost* cost, std::map<uint32_t, double>* log_scales) {
  // The guesses follow one rule (1.2 x the longest side), so they tend to be off alike, and
  // camera-by-camera rounds alone, each camera answering the others' wrong values, stay near a
  // jointly wrong start (without the common start, Herz-Jesus-P8 with a camera per image stayed
  // far from its true focal length). So all start at the one focal length over the longest side
  // that fits their pairs best. Given focal lengths join that search where there are any: from
  // internet photos, many are far off (a crop's, a resize's without the original size), and
  // camera-by-camera rounds from them stayed far off too; each given camera then starts at its
  // own value or the common one, whichever fits its pairs better.
  bool any_given = false;
  for (const auto& [camera_id, terms] : estimable) any_given = any_given || given.at(camera_id);
  std::map<uint32_t, double> offsets;  // log(longest side / prior): log scale at ratio 1
  std::set<const FundamentalPair*> linked;
  for (const auto& [camera_id, terms] : estimable) {
    if (given.at(camera_id)) continue;
    offsets[camera_id] = ranges.at(camera_id).low - std::log(options.min_focal_ratio);
    linked.insert(terms->pairs.begin(), terms->pairs.end());
  }
  const size_t num_guessed = offsets.size();
  if (any_given) {
    for (const auto& [camera_id, terms] : estimable) {
      offsets[camera_id] = ranges.at(camera_id).low - std::log(options.min_focal_ratio);
      linked.insert(terms->pairs.begin(), terms->pairs.end());
    }
  }
  if (num_guessed > 1 || (any_given && offsets.size() > 1)) {
    const std::vector<const FundamentalPair*> linked_pairs(linked.begin(), linked.end());
    bool edge = false;
    const double common = MinimiseOverLogScale(
        [&](double log_ratio) { return cost->EvaluateCommon(offsets, linked_pairs, log_ratio); },
        std::log(options.min_focal_ratio), std::log(options.max_focal_ratio), &edge);
    cost->EvaluateCommon(offsets, linked_pairs, common);  // every camera at the common start
    for (const auto& [camera_id, terms] : estimable) {
      if (!given.at(camera_id)) continue;
      const double at_common = cost->Evaluate(camera_id, *terms, log_scales->at(camera_id));
      const double at_given = cost->Evaluate(camera_id, *terms, 0.0);
      (*log_scales)[camera_id] = at_given <= at_common ? 0.0 : offsets.at(camera_id) + common;
    }
  }
  std::map<uint32_t, EstimateShape> shapes;
  // Rounds let each camera answer the others' new values: one camera alone (every image sharing
  // one guess) has nothing to answer, and a second round would search the same cost again.
  const int num_rounds = estimable.size() > 1 ? options.num_rounds : 1;
  for (int round = 0; round < num_rounds; ++round) {
    for (const auto& [camera_id, terms] : estimable) {
      auto at = [&, id = camera_id, t = terms](double log_scale) {
        return cost->Evaluate(id, *t, log_scale);
      };
      EstimateShape& shape = shapes[camera_id];
      const LogRange range = RoundRange(ranges.at(camera_id), *log_scales, camera_id, options);
      const double best = MinimiseOverLogScale(at, range.low, range.high, &shape.at_edge);
      shape.at_edge = shape.at_edge && (best <= ranges.at(camera_id).low + kGridStep ||
                                        best >= ranges.at(camera_id).high - kGridStep);
      shape.cost_rise = CostRise(cost, camera_id, *terms, best);
      (*log_scales)[camera_id] = best;
    }
  }
  return shapes;
}

// The robust cost of `pairs` (all of `estimable`'s) with every estimable camera's log scale moved
// by `shift` from `log_scales`.
double JointCost(const std::map<uint32_t, const CameraTerms*>& estimable,
                 const std::vector<const FundamentalPair*>& pairs, FocalCost* cost,
                 const std::map<uint32_t, double>& log_scales, double shift,
                 std::map<uint32_t, double>* current) {
  for (const auto& [camera_id, terms] : estimable)
    (*current)[camera_id] = log_scales.at(camera_id) + shift;
  double total = 0.0;
  for (const FundamentalPair* pair : pairs)
    total += CauchyLoss(cost->PairCost(*pair), cost->loss_scale());
  return total;
}

// Where views all look at one point (a landmark photographed from around it, a turntable), the
// pairs fix the focal lengths' ratios but hardly their common scale: scaling every estimate
// together changes the joint cost little, though each camera alone, the others held, is well
// determined. Coordinate descent then drifts along that valley towards whichever start pulls
// hardest: a two-image camera whose EXIF is 10x off drags a fourteen-image camera with the right
// value 20% along. Where some focal lengths are given, their consensus sets the scale the views
// cannot: every estimate is moved together so that the given cameras' median log ratio of
// estimate to given value (weighted by their pairs) is zero, where that raises the joint cost by
// less than min_cost_rise; the pairs keep the ratios. Returns whether it moved them.
bool ScaleFromGivenFocalLengths(const std::map<uint32_t, const CameraTerms*>& estimable,
                                const std::map<uint32_t, bool>& given,
                                const ViewGraphCalibrationOptions& options, FocalCost* cost,
                                std::map<uint32_t, double>* log_scales) {
  std::vector<std::pair<double, double>> given_ratios;  // log(estimate / given), weight
  for (const auto& [camera_id, terms] : estimable) {
    if (given.at(camera_id)) {
      given_ratios.emplace_back(log_scales->at(camera_id),
                                static_cast<double>(terms->pairs.size()));
    }
  }
  if (given_ratios.empty()) return false;
  const std::map<uint32_t, double> estimate = *log_scales;
  std::set<const FundamentalPair*> linked;
  for (const auto& [camera_id, terms] : estimable)
    linked.insert(terms->pairs.begin(), terms->pairs.end());
  const std::vector<const FundamentalPair*> pairs(linked.begin(), linked.end());
  auto joint = [&](double shift) {
    return JointCost(estimable, pairs, cost, estimate, shift, log_scales);
  };
  size_t num_pairs = 0;
  for (const auto& [camera_id, terms] : estimable) num_pairs += terms->pairs.size();
  const double floor = num_pairs * CauchyLoss(0.002, cost->loss_scale());
  const double minimum = std::max(joint(0.0), floor);
  std::sort(given_ratios.begin(), given_ratios.end());
  double total_weight = 0.0;
  for (const auto& [ratio, weight] : given_ratios) total_weight += weight;
  double median = given_ratios.back().first, accumulated = 0.0;
  for (const auto& [ratio, weight] : given_ratios) {
    accumulated += weight;
    if (accumulated >= 0.5 * total_weight) {
      median = ratio;
      break;
    }
  }
  // The given values choose the scale only within what the pairs allow: moved there, the joint
  // cost may rise by less than min_cost_rise (CostRise's test of a determined estimate).
  if (std::abs(median) < 1e-9 || joint(-median) - minimum >= options.min_cost_rise * minimum) {
    joint(0.0);
    return false;
  }
  return true;
}

// Why an estimate is not to be trusted; empty when it is.
std::string EstimateProblem(const CameraCalibration& result, const EstimateShape& shape,
                            const ViewGraphCalibrationOptions& options) {
  if (!std::isfinite(result.estimated_focal_px) || !(result.estimated_focal_px > 0)) {
    return "the estimate is not a positive number";
  }
  if (shape.at_edge) {
    return "the estimate sits at the edge of the search range (" +
           FormatOptionNumber(options.min_focal_ratio) + " to " +
           FormatOptionNumber(options.max_focal_ratio) + " x the longest image side)";
  }
  if (shape.cost_rise < options.min_cost_rise) {
    const std::string rise =
        shape.cost_rise > 0 ? "only " + std::to_string(static_cast<int>(100 * shape.cost_rise)) +
                                  "% above its minimum"
                            : "no higher than at the estimate";
    return "the pairs leave the focal length undetermined (the cost 20% away is " + rise +
           ": every optical axis through one point, as around a turntable, or too little "
           "rotation)";
  }
  if (result.median_cost > options.max_median_cost) {
    return "the pairs disagree (median cost " + std::to_string(result.median_cost) + " > " +
           std::to_string(options.max_median_cost) + ")";
  }
  return "";
}

}  // namespace

const char* FocalOutcomeName(FocalOutcome outcome) {
  switch (outcome) {
    case FocalOutcome::kEstimated:
      return "estimated";
    case FocalOutcome::kNotEstimated:
      return "not estimated";
    case FocalOutcome::kConfirmed:
      return "given, confirmed";
    case FocalOutcome::kDisproved:
      return "given, disproved";
    case FocalOutcome::kUntested:
      return "given, untested";
  }
  return "";
}

namespace {

// The outcome of a camera whose estimate was judged (`result.problem` set when not trusted).
FocalOutcome OutcomeOf(const CameraCalibration& result,
                       const ViewGraphCalibrationOptions& options) {
  if (!result.given) {
    return result.problem.empty() ? FocalOutcome::kEstimated : FocalOutcome::kNotEstimated;
  }
  if (!result.problem.empty()) return FocalOutcome::kUntested;
  const double distance = std::abs(std::log(result.estimated_focal_px / result.prior_focal_px));
  return distance <= std::log1p(options.given_focal_tolerance) ? FocalOutcome::kConfirmed
                                                               : FocalOutcome::kDisproved;
}

}  // namespace

namespace {

// What the estimation works on: the cameras to estimate (and whether each is given), the camera
// each is estimated as, and the pairs of each. Filled in place (SetUpCalibration, after
// to_estimate): `terms` points into `pairs`.
struct CalibrationSetup {
  std::map<uint32_t, bool> to_estimate;
  std::map<uint32_t, uint32_t> estimated_as;  // identical cameras: the lowest id among them
  std::vector<FundamentalPair> pairs;
  std::map<uint32_t, CameraTerms> terms;
  std::map<uint32_t, const CameraTerms*> estimable;  // at least min_num_pairs pairs
  std::map<uint32_t, LogRange> ranges;
};

void SetUpCalibration(const FeatureDatabase& database, const ViewGraphCalibrationOptions& options,
                      const std::map<uint32_t, Camera>& cameras, bool share_identical_cameras,
                      CalibrationSetup* setup) {
  for (const auto& [camera_id, camera] : cameras) setup->estimated_as[camera_id] = camera_id;
  if (share_identical_cameras) setup->estimated_as = IdenticalCameras(cameras);
  setup->pairs = PairsWithFundamentalMatrix(database, options.min_num_inliers);
  for (FundamentalPair& pair : setup->pairs) {
    if (setup->estimated_as.count(pair.camera1))
      pair.camera1 = setup->estimated_as.at(pair.camera1);
    if (setup->estimated_as.count(pair.camera2))
      pair.camera2 = setup->estimated_as.at(pair.camera2);
  }
  setup->terms = TermsOfCameras(setup->pairs, setup->to_estimate, cameras, options);
  for (const auto& [camera_id, camera_terms] : setup->terms) {
    if (static_cast<int>(camera_terms.pairs.size()) >= options.min_num_pairs) {
      setup->estimable[camera_id] = &camera_terms;
      setup->ranges[camera_id] = SearchRange(cameras.at(camera_id), options);
    }
  }
}

// Each camera judged at the current log scales: its estimate, its pairs' median cost, why it is
// not trusted, its outcome.
std::vector<CameraCalibration> JudgeCameras(const CalibrationSetup& setup,
                                            const std::map<uint32_t, EstimateShape>& shapes,
                                            const std::map<uint32_t, double>& log_scales,
                                            const std::map<uint32_t, Camera>& cameras,
                                            const ViewGraphCalibrationOptions& options,
                                            FocalCost* cost) {
  std::vector<CameraCalibration> judged;
  for (const auto& [member, given] : setup.to_estimate) {
    const uint32_t camera_id = setup.estimated_as.at(member);
    CameraCalibration result;
    result.camera_id = member;
    result.given = given;
    result.prior_focal_px = MeanFocalLength(cameras.at(camera_id));
    const auto found = setup.terms.find(camera_id);
    result.num_pairs =
        found == setup.terms.end() ? 0 : static_cast<int>(found->second.pairs.size());
    if (!setup.estimable.count(camera_id)) {
      result.problem = result.num_pairs == 0
                           ? "no verified pair with a fundamental matrix (only pure rotations "
                             "or planes?)"
                           : "only " + std::to_string(result.num_pairs) +
                                 " pairs with a fundamental matrix (needs " +
                                 std::to_string(options.min_num_pairs) + ")";
    } else {
      std::vector<double> costs;
      for (const FundamentalPair* pair : found->second.pairs)
        costs.push_back(cost->PairCost(*pair));
      result.median_cost = Median(costs);
      result.estimated_focal_px = result.prior_focal_px * std::exp(log_scales.at(camera_id));
      result.problem = EstimateProblem(result, shapes.at(camera_id), options);
    }
    result.outcome = OutcomeOf(result, options);
    result.estimated =
        result.outcome == FocalOutcome::kEstimated || result.outcome == FocalOutcome::kDisproved;
    judged.push_back(result);
  }
  return judged;
}

// A given focal length the pairs confirm is the best value there is for its camera: the others
// are estimated once more against it held, so that a disproved or unknown camera's estimate does
// not carry the joint estimate's error along the valley of the ratios. The confirmed ones keep
// their report of the joint estimate.
void EstimateAgainstConfirmed(const CalibrationSetup& setup,
                              const std::map<uint32_t, EstimateShape>& shapes,
                              const std::map<uint32_t, Camera>& cameras,
                              const ViewGraphCalibrationOptions& options, FocalCost* cost,
                              std::map<uint32_t, double>* log_scales,
                              std::vector<CameraCalibration>* judged) {
  std::map<uint32_t, const CameraTerms*> others;
  bool any_confirmed = false;
  for (const CameraCalibration& result : *judged) {
    const uint32_t camera_id = setup.estimated_as.at(result.camera_id);
    if (!setup.estimable.count(camera_id)) continue;
    if (result.outcome == FocalOutcome::kConfirmed) {
      (*log_scales)[camera_id] = 0.0;
      any_confirmed = true;
    } else {
      others[camera_id] = setup.estimable.at(camera_id);
    }
  }
  if (!any_confirmed || others.empty()) return;
  std::map<uint32_t, EstimateShape> anchored = shapes;
  for (const auto& [camera_id, camera_terms] : others) {
    auto at = [&, id = camera_id, t = camera_terms](double log_scale) {
      return cost->Evaluate(id, *t, log_scale);
    };
    EstimateShape& shape = anchored[camera_id];
    const LogRange range = RoundRange(setup.ranges.at(camera_id), *log_scales, camera_id, options);
    const double best = MinimiseOverLogScale(at, range.low, range.high, &shape.at_edge);
    shape.cost_rise = CostRise(cost, camera_id, *camera_terms, best);
    (*log_scales)[camera_id] = best;
  }
  const std::vector<CameraCalibration> again =
      JudgeCameras(setup, anchored, *log_scales, cameras, options, cost);
  for (size_t k = 0; k < again.size(); ++k) {
    if ((*judged)[k].outcome != FocalOutcome::kConfirmed) (*judged)[k] = again[k];
  }
}

}  // namespace

ViewGraphCalibrationSummary CalibrateFocalLengths(const FeatureDatabase& database,
                                                  const ViewGraphCalibrationOptions& options,
                                                  std::map<uint32_t, Camera>* cameras,
                                                  bool share_identical_cameras) {
  options.Check();
  Timer timer;
  ViewGraphCalibrationSummary summary;
  CalibrationSetup setup;
  setup.to_estimate = CamerasToEstimate(database, *cameras, options);
  if (!options.enable || setup.to_estimate.empty()) return summary;
  SetUpCalibration(database, options, *cameras, share_identical_cameras, &setup);

  std::map<uint32_t, double> log_scales;  // estimable cameras only; absent = prior
  FocalCost cost(*cameras, options, &log_scales);
  const std::map<uint32_t, EstimateShape> shapes = EstimateLogScales(
      setup.estimable, setup.to_estimate, setup.ranges, options, &cost, &log_scales);
  const std::map<uint32_t, double> pairs_only = log_scales;  // before the given values' scale
  summary.scale_from_given =
      ScaleFromGivenFocalLengths(setup.estimable, setup.to_estimate, options, &cost, &log_scales);
  // Every camera is judged at the joint estimate first; the parameters change only afterwards (the
  // cost reads them).
  summary.cameras = JudgeCameras(setup, shapes, log_scales, *cameras, options, &cost);
  EstimateAgainstConfirmed(setup, shapes, *cameras, options, &cost, &log_scales, &summary.cameras);
  // A confirmed camera reports what its pairs said, before the given values set the scale (one
  // given camera alone would otherwise always report its given value).
  for (CameraCalibration& result : summary.cameras) {
    const auto own = pairs_only.find(setup.estimated_as.at(result.camera_id));
    if (result.outcome == FocalOutcome::kConfirmed && own != pairs_only.end())
      result.estimated_focal_px = result.prior_focal_px * std::exp(own->second);
  }
  for (const CameraCalibration& result : summary.cameras) {
    if (!result.estimated) continue;
    Camera& camera = cameras->at(result.camera_id);
    const double factor = std::exp(log_scales.at(setup.estimated_as.at(result.camera_id)));
    camera.params[0] *= factor;
    if (!HasSingleFocalLength(camera.model)) camera.params[1] *= factor;
    // A disproved focal length is a start from here on, as a guess is: refined, never held.
    camera.has_prior_focal_length = false;
  }
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
