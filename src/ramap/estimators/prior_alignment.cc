#include "ramap/estimators/prior_alignment.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "ramap/geometry/rotation.h"
#include "ramap/util/error.h"
#include "ramap/util/statistics.h"

namespace ramap {

void PriorAlignmentOptions::Check() const { CheckOptionValues(PriorAlignmentOptionTable(), *this); }

namespace {

// Why the priors cannot fix the model's rotation (empty when they can): spread over too little
// for their standard deviation `sigma`, the fit's rotation would be uncertain by more than
// max_fit_uncertainty_deg. Priors that all coincide get AlignPoints's own message later.
std::string FitUncertaintyProblem(const std::vector<Eigen::Vector3d>& target, double sigma,
                                  const PriorAlignmentOptions& options) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : target) centroid += p / static_cast<double>(target.size());
  double spread = 0.0;
  for (const Eigen::Vector3d& p : target) spread += (p - centroid).squaredNorm() / target.size();
  spread = std::sqrt(spread);
  const bool coincident = CheckPointSpread(target, AlignmentOptions().min_spread_ratio) ==
                          AlignmentStatus::kCoincidentPoints;
  const double uncertainty_deg =
      sigma / (spread * std::sqrt(static_cast<double>(target.size()))) * kRadToDeg;
  if (!(uncertainty_deg > options.max_fit_uncertainty_deg) || coincident) return "";
  std::ostringstream problem;
  problem << std::fixed << std::setprecision(2) << "the priors spread over " << spread
          << " m (RMS) with a " << sigma << " m standard deviation: the fit's rotation would be "
          << "uncertain by about " << std::setprecision(1) << uncertainty_deg << " deg (> "
          << options.max_fit_uncertainty_deg << ", PosePrior.max_fit_uncertainty_deg)";
  return problem.str();
}

}  // namespace

PriorAlignment AlignCentersToPriors(const std::map<uint32_t, Eigen::Vector3d>& centers,
                                    const PosePriors& priors,
                                    const PriorAlignmentOptions& options) {
  options.Check();
  PriorAlignment result;
  PriorAlignmentSummary& summary = result.summary;
  std::vector<uint32_t> ids;
  std::vector<Eigen::Vector3d> source, target;
  std::vector<double> sigmas;
  for (const auto& [id, center] : centers) {
    const auto prior = priors.by_image.find(id);
    if (prior == priors.by_image.end()) continue;
    ids.push_back(id);
    source.push_back(center);
    target.push_back(prior->second.center);
    sigmas.push_back(prior->second.std_dev_m.norm());
  }
  summary.num_priors = static_cast<int>(ids.size());
  if (summary.num_priors < options.min_num_inliers) {
    summary.problem = std::to_string(summary.num_priors) + " registered images have a prior (" +
                      std::to_string(options.min_num_inliers) + " needed)";
    return result;
  }
  const double sigma = Median(sigmas);
  summary.threshold_m =
      options.max_alignment_error_m > 0 ? options.max_alignment_error_m : 3.0 * sigma;
  summary.problem = FitUncertaintyProblem(target, sigma, options);
  if (!summary.problem.empty()) return result;
  AlignmentOptions alignment_options;
  alignment_options.estimate_scale = true;
  alignment_options.robust = true;
  alignment_options.robust_max_error = summary.threshold_m;
  const AlignmentResult alignment = AlignPoints(source, target, alignment_options);
  if (!alignment.ok()) {
    const AlignmentStatus status = alignment.status;
    summary.problem =
        status == AlignmentStatus::kCoincidentPoints
            ? "the priors (or the model's centres) all coincide: no rotation or scale follows"
        : status == AlignmentStatus::kCollinearPoints
            ? "the priors (or the model's centres) lie on one line: the rotation about it is free"
            : std::string("no similarity fits ") + std::to_string(options.min_num_inliers) +
                  " or more priors within " + std::to_string(summary.threshold_m) + " m (" +
                  AlignmentStatusName(status) + ")";
    return result;
  }
  if (alignment.num_inliers < options.min_num_inliers) {
    summary.problem = "only " + std::to_string(alignment.num_inliers) + " of " +
                      std::to_string(summary.num_priors) + " priors agree within " +
                      std::to_string(summary.threshold_m) + " m (" +
                      std::to_string(options.min_num_inliers) + " needed)";
    return result;
  }
  result.prior_from_model = alignment.target_from_source;
  double sum_squares = 0.0;
  for (size_t k = 0; k < ids.size(); ++k) {
    const double error = (result.prior_from_model * source[k] - target[k]).norm();
    if (alignment.inliers[k]) {
      sum_squares += error * error;
      result.inliers[ids[k]] = priors.by_image.at(ids[k]);
    } else {
      summary.outliers.push_back({ids[k], error});
    }
  }
  std::sort(summary.outliers.begin(), summary.outliers.end(),
            [](const PriorOutlier& a, const PriorOutlier& b) { return a.error_m > b.error_m; });
  summary.num_inliers = alignment.num_inliers;
  summary.rmse_m = std::sqrt(sum_squares / alignment.num_inliers);
  summary.scale = result.prior_from_model.scale;
  summary.aligned = true;
  return result;
}

std::vector<PosePriorInModel> PriorsInModelFrame(const PriorAlignment& alignment) {
  const Sim3d model_from_prior = alignment.prior_from_model.Inverse();
  // r = diag(1/sigma) (s R c + t - p) = diag(1/sigma) s R (c - model_from_prior * p).
  const Eigen::Matrix3d scaled_rotation =
      alignment.prior_from_model.scale * alignment.prior_from_model.rotation.toRotationMatrix();
  std::vector<PosePriorInModel> priors;
  for (const auto& [id, prior] : alignment.inliers) {
    priors.push_back({id, model_from_prior * prior.center,
                      prior.std_dev_m.cwiseInverse().asDiagonal() * scaled_rotation});
  }
  return priors;
}

void MeasurePriorErrors(const Reconstruction& reconstruction, const PosePriors& priors,
                        const std::map<uint32_t, PosePrior>& inliers,
                        PriorAlignmentSummary* summary) {
  auto error = [&](uint32_t id) {
    return (CameraCenter(reconstruction.images.at(id).cam_from_world) -
            priors.by_image.at(id).center)
        .norm();
  };
  double sum_squares = 0.0;
  int count = 0;
  for (const auto& [id, prior] : inliers) {
    if (!reconstruction.images.count(id)) continue;
    sum_squares += std::pow(error(id), 2);
    ++count;
  }
  if (count > 0) summary->rmse_m = std::sqrt(sum_squares / count);
  for (PriorOutlier& outlier : summary->outliers) {
    if (reconstruction.images.count(outlier.image_id)) outlier.error_m = error(outlier.image_id);
  }
}

void TransformReconstruction(const Sim3d& new_from_old, Reconstruction* reconstruction) {
  for (auto& [id, image] : reconstruction->images) {
    image.cam_from_world = TransformPose(new_from_old, image.cam_from_world);
  }
  for (auto& [id, point] : reconstruction->points3D) point.xyz = new_from_old * point.xyz;
}

PriorAlignment AlignModelToPriors(const PosePriors& priors, const PriorAlignmentOptions& options,
                                  Reconstruction* model) {
  std::map<uint32_t, Eigen::Vector3d> centers;
  for (const auto& [id, image] : model->images) centers[id] = CameraCenter(image.cam_from_world);
  PriorAlignment alignment = AlignCentersToPriors(centers, priors, options);
  if (alignment.summary.aligned) TransformReconstruction(alignment.prior_from_model, model);
  return alignment;
}

}  // namespace ramap
