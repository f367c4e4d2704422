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

  // The same with every camera of `camera_ids` at one common log scale, over `pairs`.
  double EvaluateCommon(const std::vector<uint32_t>& camera_ids,
                        const std::vector<const FundamentalPair*>& pairs, double log_scale) {
    for (const uint32_t camera_id : camera_ids) log_scales_[camera_id] = log_scale;
    double total = 0.0;
    for (const FundamentalPair* pair : pairs) {
      total += CauchyLoss(PairCost(*pair), options_.loss_scale);
    }
    const double prior = log_scale / std::log(2.0);
    return total + options_.prior_weight * camera_ids.size() * prior * prior;
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
template <typename Cost>
double MinimiseOverLogScale(Cost&& cost, double low, double high, bool* at_edge) {
  constexpr int kSamples = 241;
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
  CheckOption(min_focal_factor > 0 && min_focal_factor < 1, s + "min_focal_factor", "in (0, 1)",
              min_focal_factor);
  CheckOption(max_focal_factor > 1 && std::isfinite(max_focal_factor), s + "max_focal_factor",
              "finite and > 1", max_focal_factor);
  CheckOption(min_num_inliers >= 8, s + "min_num_inliers", ">= 8", min_num_inliers);
  CheckOption(max_pairs_per_camera >= 1, s + "max_pairs_per_camera", ">= 1", max_pairs_per_camera);
  CheckOption(loss_scale > 0, s + "loss_scale", "> 0", loss_scale);
  CheckOption(prior_weight >= 0, s + "prior_weight", ">= 0", prior_weight);
  CheckOption(num_rounds >= 1, s + "num_rounds", ">= 1", num_rounds);
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

// The cameras the database marks unknown (prior_focal_length 0), fisheye models aside.
std::set<uint32_t> UnknownCameras(const FeatureDatabase& database,
                                  const std::map<uint32_t, Camera>& cameras) {
  std::set<uint32_t> unknown;
  for (const auto& [camera_id, camera] : cameras) {
    const auto stored = database.cameras.find(camera_id);
    if (stored != database.cameras.end() && !stored->second.has_prior_focal_length &&
        !IsFisheyeModel(camera.model)) {
      unknown.insert(camera_id);
    }
  }
  return unknown;
}

// The pairs of each unknown camera, at most max_pairs_per_camera (those with the most inliers).
std::map<uint32_t, CameraTerms> TermsOfUnknownCameras(const std::vector<FundamentalPair>& pairs,
                                                      const std::set<uint32_t>& unknown,
                                                      const std::map<uint32_t, Camera>& cameras,
                                                      const ViewGraphCalibrationOptions& options) {
  std::map<uint32_t, CameraTerms> terms;
  for (const FundamentalPair& pair : pairs) {
    if (!cameras.count(pair.camera1) || !cameras.count(pair.camera2)) continue;
    for (const uint32_t id : {pair.camera1, pair.camera2}) {
      if (unknown.count(id)) terms[id].pairs.push_back(&pair);
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

// Minimises the cost over the log scales of the cameras in `estimable` (each with at least
// min_num_pairs pairs): first one common factor for all of them, then camera by camera.
std::map<uint32_t, EstimateShape> EstimateLogScales(
    const std::map<uint32_t, const CameraTerms*>& estimable,
    const ViewGraphCalibrationOptions& options, FocalCost* cost,
    std::map<uint32_t, double>* log_scales) {
  const double low = std::log(options.min_focal_factor);
  const double high = std::log(options.max_focal_factor);
  // The guesses follow one rule (1.2 x the longest side), so they tend to be off alike, and
  // camera-by-camera rounds alone, each camera answering the others' wrong values, stay near a
  // jointly wrong start (without the common start, Herz-Jesus-P8 with a camera per image stayed
  // far from its true focal length).
  if (estimable.size() > 1) {
    std::vector<uint32_t> ids;
    std::set<const FundamentalPair*> linked;
    for (const auto& [camera_id, terms] : estimable) {
      ids.push_back(camera_id);
      linked.insert(terms->pairs.begin(), terms->pairs.end());
    }
    const std::vector<const FundamentalPair*> linked_pairs(linked.begin(), linked.end());
    bool edge = false;
    const double common = MinimiseOverLogScale(
        [&](double log_scale) { return cost->EvaluateCommon(ids, linked_pairs, log_scale); }, low,
        high, &edge);
    for (const uint32_t camera_id : ids) (*log_scales)[camera_id] = common;
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
      const double best = MinimiseOverLogScale(at, low, high, &shape.at_edge);
      shape.cost_rise = CostRise(cost, camera_id, *terms, best);
      (*log_scales)[camera_id] = best;
    }
  }
  return shapes;
}

// Why an estimate is not to be trusted; empty when it is.
std::string EstimateProblem(const CameraCalibration& result, const EstimateShape& shape,
                            const ViewGraphCalibrationOptions& options) {
  if (!std::isfinite(result.estimated_focal_px) || !(result.estimated_focal_px > 0)) {
    return "the estimate is not a positive number";
  }
  if (shape.at_edge) {
    return "the estimate sits at the edge of the search range (" +
           std::to_string(options.min_focal_factor) + " to " +
           std::to_string(options.max_focal_factor) + " x the prior)";
  }
  if (shape.cost_rise < options.min_cost_rise) {
    const std::string rise =
        shape.cost_rise > 0
            ? "only " + std::to_string(static_cast<int>(100 * shape.cost_rise)) +
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

ViewGraphCalibrationSummary CalibrateFocalLengths(const FeatureDatabase& database,
                                                  const ViewGraphCalibrationOptions& options,
                                                  std::map<uint32_t, Camera>* cameras,
                                                  bool share_identical_cameras) {
  options.Check();
  Timer timer;
  ViewGraphCalibrationSummary summary;
  const std::set<uint32_t> unknown = UnknownCameras(database, *cameras);
  if (!options.enable || unknown.empty()) return summary;
  // Identical cameras are estimated as one, through the lowest id among them.
  std::map<uint32_t, uint32_t> estimated_as;
  for (const auto& [camera_id, camera] : *cameras) estimated_as[camera_id] = camera_id;
  if (share_identical_cameras) estimated_as = IdenticalCameras(*cameras);

  std::vector<FundamentalPair> pairs =
      PairsWithFundamentalMatrix(database, options.min_num_inliers);
  for (FundamentalPair& pair : pairs) {
    if (estimated_as.count(pair.camera1)) pair.camera1 = estimated_as.at(pair.camera1);
    if (estimated_as.count(pair.camera2)) pair.camera2 = estimated_as.at(pair.camera2);
  }
  const std::map<uint32_t, CameraTerms> terms =
      TermsOfUnknownCameras(pairs, unknown, *cameras, options);
  std::map<uint32_t, const CameraTerms*> estimable;
  for (const auto& [camera_id, camera_terms] : terms) {
    if (static_cast<int>(camera_terms.pairs.size()) >= options.min_num_pairs) {
      estimable[camera_id] = &camera_terms;
    }
  }
  std::map<uint32_t, double> log_scales;  // estimable cameras only; absent = prior
  FocalCost cost(*cameras, options, &log_scales);
  const std::map<uint32_t, EstimateShape> shapes =
      EstimateLogScales(estimable, options, &cost, &log_scales);

  // Every camera is judged at the joint estimate first; the parameters change only afterwards (the
  // cost reads them).
  for (const uint32_t member : unknown) {
    const uint32_t camera_id = estimated_as.at(member);
    CameraCalibration result;
    result.camera_id = member;
    result.prior_focal_px = MeanFocalLength(cameras->at(camera_id));
    const auto found = terms.find(camera_id);
    result.num_pairs = found == terms.end() ? 0 : static_cast<int>(found->second.pairs.size());
    if (!estimable.count(camera_id)) {
      result.problem = result.num_pairs == 0
                           ? "no verified pair with a fundamental matrix (only pure rotations or "
                             "planes?)"
                           : "only " + std::to_string(result.num_pairs) +
                                 " pairs with a fundamental matrix (needs " +
                                 std::to_string(options.min_num_pairs) + ")";
    } else {
      std::vector<double> costs;
      for (const FundamentalPair* pair : found->second.pairs) costs.push_back(cost.PairCost(*pair));
      result.median_cost = Median(costs);
      result.estimated_focal_px = result.prior_focal_px * std::exp(log_scales.at(camera_id));
      result.problem = EstimateProblem(result, shapes.at(camera_id), options);
      result.estimated = result.problem.empty();
    }
    summary.cameras.push_back(result);
  }
  for (const CameraCalibration& result : summary.cameras) {
    if (!result.estimated) continue;
    Camera& camera = cameras->at(result.camera_id);
    const double factor = std::exp(log_scales.at(estimated_as.at(result.camera_id)));
    camera.params[0] *= factor;
    if (!HasSingleFocalLength(camera.model)) camera.params[1] *= factor;
  }
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
