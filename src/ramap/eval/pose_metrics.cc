#include "ramap/eval/pose_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "ramap/geometry/rotation.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/staged_output.h"

namespace ramap {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double Median(std::vector<double> values) {
  if (values.empty()) return kNaN;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  // Both infinite: the mean would be NaN for (-inf, inf) only, which errors never are.
  return 0.5 * (lower + upper);
}

double Mean(const std::vector<double>& values) {
  if (values.empty()) return kNaN;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double Max(const std::vector<double>& values) {
  if (values.empty()) return kNaN;
  return *std::max_element(values.begin(), values.end());
}

double Rms(const std::vector<double>& values) {
  if (values.empty()) return kNaN;
  double sum_sq = 0.0;
  for (double v : values) sum_sq += v * v;
  return std::sqrt(sum_sq / static_cast<double>(values.size()));
}

nlohmann::json Number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

const char* AucDefinitionName(AucDefinition definition) {
  return definition == AucDefinition::kBenchmarkTrapezoid ? "benchmark_trapezoid" : "step_integral";
}

}  // namespace

void PoseEvaluationOptions::Check() const {
  CheckOptionValues(PoseEvaluationOptionTable(), *this);
  CheckOption(!alignment.robust || alignment.robust_max_error > 0, "--robust_alignment_max_error",
              "> 0 with --robust_alignment 1 (in ground-truth units)", alignment.robust_max_error);
  alignment.Check();
}

PairPoseError RelativePoseError(const Rigid3d& est_i, const Rigid3d& est_j, const Rigid3d& gt_i,
                                const Rigid3d& gt_j, double min_baseline) {
  const Rigid3d rel_est = est_j * est_i.Inverse();
  const Rigid3d rel_gt = gt_j * gt_i.Inverse();
  PairPoseError error;
  error.rotation_deg = RotationAngleDeg(rel_gt.rotation, rel_est.rotation);
  if (rel_gt.translation.norm() <= min_baseline) {
    error.translation_deg = 0.0;  // no direction to compare against
  } else if (rel_est.translation.norm() == 0.0) {
    error.translation_deg = 180.0;  // the estimate has no direction at all: worst case
  } else {
    error.translation_deg = AngleBetween(rel_est.translation, rel_gt.translation) * kRadToDeg;
  }
  return error;
}

std::map<std::string, Rigid3d> PosesByName(const Reconstruction& reconstruction,
                                           const std::string& source) {
  std::map<std::string, Rigid3d> poses;
  for (const auto& [image_id, image] : reconstruction.images) {
    if (!poses.emplace(image.name, image.cam_from_world).second) {
      throw InputError(source, "two registered images are named '" + image.name + "'");
    }
  }
  return poses;
}

namespace {

// The images of the evaluation, in input order, with pointers to their poses where they have one.
struct EvaluatedImages {
  std::vector<const Rigid3d*> estimated;
  std::vector<const Rigid3d*> ground_truth;
  std::vector<int> evaluated;  // registered with ground truth
  std::vector<int> with_gt;    // with ground truth, input order
};

// Fills the per-image rows and counts of `result`; throws InputError on a repeated name.
EvaluatedImages MatchImages(const std::map<std::string, Rigid3d>& estimated,
                            const std::map<std::string, Rigid3d>& ground_truth,
                            const std::vector<std::string>& all_image_names,
                            PoseEvaluation* result) {
  std::unordered_map<std::string, int> input_index;
  for (const std::string& name : all_image_names) {
    if (!input_index.emplace(name, static_cast<int>(input_index.size())).second) {
      throw InputError("image list", "image name '" + name + "' appears twice");
    }
  }
  for (const auto& [name, pose] : estimated) {
    if (input_index.count(name) == 0) ++result->num_estimated_not_in_input;
  }
  const int n = result->num_images;
  EvaluatedImages images{
      std::vector<const Rigid3d*>(n, nullptr), std::vector<const Rigid3d*>(n, nullptr), {}, {}};
  result->images.resize(n);
  for (int i = 0; i < n; ++i) {
    ImageEvaluation& image = result->images[i];
    image.name = all_image_names[i];
    if (auto it = estimated.find(image.name); it != estimated.end()) {
      images.estimated[i] = &it->second;
    }
    if (auto it = ground_truth.find(image.name); it != ground_truth.end()) {
      images.ground_truth[i] = &it->second;
    }
    image.registered = images.estimated[i] != nullptr;
    image.has_ground_truth = images.ground_truth[i] != nullptr;
    result->num_registered += image.registered;
    result->num_with_ground_truth += image.has_ground_truth;
    if (image.has_ground_truth) images.with_gt.push_back(i);
    if (image.registered && image.has_ground_truth) images.evaluated.push_back(i);
  }
  result->num_evaluated = static_cast<int>(images.evaluated.size());
  return images;
}

// Scene size from the ground truth alone: path length and extent about the centroid.
void MeasureScene(const EvaluatedImages& images, PoseEvaluation* result) {
  std::vector<Eigen::Vector3d> gt_centres;
  for (int i : images.with_gt) gt_centres.push_back(CameraCenter(*images.ground_truth[i]));
  for (size_t k = 1; k < gt_centres.size(); ++k) {
    result->gt_path_length += (gt_centres[k] - gt_centres[k - 1]).norm();
  }
  if (gt_centres.empty()) return;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : gt_centres) centroid += c;
  centroid /= static_cast<double>(gt_centres.size());
  for (const Eigen::Vector3d& c : gt_centres) {
    result->gt_extent = std::max(result->gt_extent, (c - centroid).norm());
  }
}

// The Sim(3) alignment of the camera centres, then each image's position and rotation error and
// their statistics.
void AbsoluteErrors(const EvaluatedImages& images, const PoseEvaluationOptions& options,
                    PoseEvaluation* result) {
  std::vector<Eigen::Vector3d> source;
  std::vector<Eigen::Vector3d> target;
  for (int i : images.evaluated) {
    source.push_back(CameraCenter(*images.estimated[i]));
    target.push_back(CameraCenter(*images.ground_truth[i]));
  }
  const AlignmentResult alignment = AlignPoints(source, target, options.alignment);
  result->alignment_status = alignment.status;
  result->num_alignment_inliers = alignment.num_inliers;
  std::vector<double> position_errors;
  std::vector<double> rotation_errors;
  if (alignment.ok()) {
    result->gt_from_estimate = alignment.target_from_source;
    for (size_t k = 0; k < images.evaluated.size(); ++k) {
      const int i = images.evaluated[k];
      ImageEvaluation& image = result->images[i];
      const Rigid3d aligned = TransformPose(alignment.target_from_source, *images.estimated[i]);
      image.alignment_inlier = alignment.inliers[k];
      image.position_error = (CameraCenter(aligned) - target[k]).norm();
      image.rotation_error_deg =
          RotationAngleDeg(images.ground_truth[i]->rotation, aligned.rotation);
      position_errors.push_back(image.position_error);
      rotation_errors.push_back(image.rotation_error_deg);
    }
  }
  result->ate_rmse = Rms(position_errors);
  result->ate_mean = Mean(position_errors);
  result->ate_median = Median(position_errors);
  result->ate_max = Max(position_errors);
  result->ate_rmse_over_path_length =
      result->gt_path_length > 0.0 ? result->ate_rmse / result->gt_path_length : kNaN;
  result->ate_rmse_over_extent =
      result->gt_extent > 0.0 ? result->ate_rmse / result->gt_extent : kNaN;
  result->rotation_error_median_deg = Median(rotation_errors);
  result->rotation_error_mean_deg = Mean(rotation_errors);
  result->rotation_error_max_deg = Max(rotation_errors);
}

// The share of pairs within each of kRecallCurveSteps + 1 thresholds from 0 to the largest AUC
// threshold: the curve whose area the AUC is, for plotting.
void RecallCurve(std::vector<double> pair_errors, const std::vector<double>& auc_thresholds_deg,
                 PoseEvaluation* result) {
  constexpr int kRecallCurveSteps = 100;
  if (pair_errors.empty() || auc_thresholds_deg.empty()) return;
  std::sort(pair_errors.begin(), pair_errors.end());
  const double largest = *std::max_element(auc_thresholds_deg.begin(), auc_thresholds_deg.end());
  for (int k = 0; k <= kRecallCurveSteps; ++k) {
    const double threshold = largest * k / kRecallCurveSteps;
    const auto within = std::upper_bound(pair_errors.begin(), pair_errors.end(), threshold);
    result->recall_curve_thresholds_deg.push_back(threshold);
    result->recall_curve.push_back(static_cast<double>(within - pair_errors.begin()) /
                                   static_cast<double>(pair_errors.size()));
  }
}

// Relative pose errors over every pair with ground truth (no alignment involved); a pair with an
// unregistered image is a failure. Then their medians and AUC.
void RelativeErrors(const EvaluatedImages& images, const PoseEvaluationOptions& options,
                    PoseEvaluation* result) {
  std::vector<double> pair_errors;
  std::vector<double> relative_rotation_errors;
  std::vector<double> relative_translation_errors;
  auto score = [&](int i, int j) {
    const Rigid3d* est_i = images.estimated[i];
    const Rigid3d* est_j = images.estimated[j];
    if (est_i == nullptr || est_j == nullptr) {
      pair_errors.push_back(kInf);
      ++result->num_failed_pairs;
      return;
    }
    const PairPoseError e = RelativePoseError(*est_i, *est_j, *images.ground_truth[i],
                                              *images.ground_truth[j], options.min_baseline);
    relative_rotation_errors.push_back(e.rotation_deg);
    relative_translation_errors.push_back(e.translation_deg);
    pair_errors.push_back(e.error_deg());
  };
  const std::vector<int>& with_gt = images.with_gt;
  for (size_t a = 0; a < with_gt.size(); ++a) {
    for (size_t b = a + 1; b < with_gt.size(); ++b) {
      score(with_gt[a], with_gt[b]);
      if (options.ordered_pairs) score(with_gt[b], with_gt[a]);
    }
  }
  result->num_pairs = static_cast<int>(pair_errors.size());
  result->relative_rotation_error_median_deg = Median(relative_rotation_errors);
  result->relative_translation_error_median_deg = Median(relative_translation_errors);
  result->pair_error_median_deg = Median(pair_errors);
  result->auc = ComputeAuc(pair_errors, options.auc_thresholds_deg, options.auc_definition);
  RecallCurve(pair_errors, options.auc_thresholds_deg, result);
}

}  // namespace

PoseEvaluation EvaluatePoses(const std::map<std::string, Rigid3d>& estimated,
                             const std::map<std::string, Rigid3d>& ground_truth,
                             const std::vector<std::string>& all_image_names,
                             const PoseEvaluationOptions& options) {
  options.Check();
  PoseEvaluation result;
  result.num_images = static_cast<int>(all_image_names.size());
  result.auc_thresholds_deg = options.auc_thresholds_deg;
  result.auc_definition = options.auc_definition;
  const EvaluatedImages images = MatchImages(estimated, ground_truth, all_image_names, &result);
  MeasureScene(images, &result);
  AbsoluteErrors(images, options, &result);
  RelativeErrors(images, options, &result);
  return result;
}

nlohmann::json PoseEvaluationToJson(const PoseEvaluation& e, bool with_images) {
  nlohmann::json j;
  j["num_images"] = e.num_images;
  j["num_registered"] = e.num_registered;
  j["num_with_ground_truth"] = e.num_with_ground_truth;
  j["num_evaluated"] = e.num_evaluated;
  j["num_estimated_not_in_input"] = e.num_estimated_not_in_input;
  j["alignment"] = {
      {"status", AlignmentStatusName(e.alignment_status)},
      {"num_inliers", e.num_alignment_inliers},
      {"scale", Number(e.gt_from_estimate.scale)},
      {"rotation_wxyz",
       {e.gt_from_estimate.rotation.w(), e.gt_from_estimate.rotation.x(),
        e.gt_from_estimate.rotation.y(), e.gt_from_estimate.rotation.z()}},
      {"translation",
       {e.gt_from_estimate.translation.x(), e.gt_from_estimate.translation.y(),
        e.gt_from_estimate.translation.z()}},
  };
  j["ate"] = {
      {"rmse", Number(e.ate_rmse)},
      {"mean", Number(e.ate_mean)},
      {"median", Number(e.ate_median)},
      {"max", Number(e.ate_max)},
      {"gt_path_length", Number(e.gt_path_length)},
      {"gt_extent", Number(e.gt_extent)},
      {"rmse_over_path_length", Number(e.ate_rmse_over_path_length)},
      {"rmse_over_extent", Number(e.ate_rmse_over_extent)},
  };
  j["rotation_error_deg"] = {
      {"median", Number(e.rotation_error_median_deg)},
      {"mean", Number(e.rotation_error_mean_deg)},
      {"max", Number(e.rotation_error_max_deg)},
  };
  nlohmann::json auc = nlohmann::json::object();
  for (size_t k = 0; k < e.auc.size(); ++k) {
    char key[32];
    std::snprintf(key, sizeof(key), "%g", e.auc_thresholds_deg[k]);
    auc[key] = Number(e.auc[k]);
  }
  j["relative"] = {
      {"num_pairs", e.num_pairs},
      {"num_failed_pairs", e.num_failed_pairs},
      {"rotation_error_median_deg", Number(e.relative_rotation_error_median_deg)},
      {"translation_error_median_deg", Number(e.relative_translation_error_median_deg)},
      {"pair_error_median_deg", Number(e.pair_error_median_deg)},
      {"auc_definition", AucDefinitionName(e.auc_definition)},
      {"auc_by_threshold_deg", auc},
  };
  // The same AUCs as parallel arrays, in threshold order (JSON objects do not keep order).
  nlohmann::json auc_values = nlohmann::json::array();
  for (double value : e.auc) auc_values.push_back(Number(value));
  j["relative"]["auc_thresholds_deg"] = e.auc_thresholds_deg;
  j["relative"]["auc"] = auc_values;
  if (with_images) {
    nlohmann::json images = nlohmann::json::array();
    for (const ImageEvaluation& image : e.images) {
      const bool scored = image.position_error >= 0.0;
      images.push_back({
          {"name", image.name},
          {"registered", image.registered},
          {"has_ground_truth", image.has_ground_truth},
          {"alignment_inlier", image.alignment_inlier},
          {"position_error", scored ? Number(image.position_error) : nlohmann::json(nullptr)},
          {"rotation_error_deg",
           scored ? Number(image.rotation_error_deg) : nlohmann::json(nullptr)},
      });
    }
    j["images"] = images;
  }
  return j;
}

void WritePoseEvaluationJson(const PoseEvaluation& evaluation, const std::string& path) {
  const std::string text = PoseEvaluationToJson(evaluation).dump(2) + "\n";
  WriteFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::string FormatPoseEvaluation(const PoseEvaluation& e) {
  std::ostringstream out;
  char line[256];
  auto row = [&](const char* label, const std::string& value) {
    std::snprintf(line, sizeof(line), "  %-38s %s\n", label, value.c_str());
    out << line;
  };
  auto num = [](double v, const char* format = "%.6g") {
    if (std::isnan(v)) return std::string("n/a");
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), format, v);
    return std::string(buffer);
  };
  out << "Pose evaluation\n";
  row("registered / input images",
      std::to_string(e.num_registered) + " / " + std::to_string(e.num_images));
  row("evaluated (registered, with GT)", std::to_string(e.num_evaluated) + " of " +
                                             std::to_string(e.num_with_ground_truth) +
                                             " with ground truth");
  row("alignment (Sim3 or SE3)", std::string(AlignmentStatusName(e.alignment_status)) + ", " +
                                     std::to_string(e.num_alignment_inliers) + " inliers, scale " +
                                     num(e.gt_from_estimate.scale));
  row("ATE RMSE / median / max",
      num(e.ate_rmse) + " / " + num(e.ate_median) + " / " + num(e.ate_max));
  row("ATE RMSE / GT path length",
      num(100.0 * e.ate_rmse_over_path_length, "%.4g") + " % of " + num(e.gt_path_length));
  row("ATE RMSE / GT extent",
      num(100.0 * e.ate_rmse_over_extent, "%.4g") + " % of " + num(e.gt_extent));
  row("rotation error median / mean (deg)",
      num(e.rotation_error_median_deg, "%.4g") + " / " + num(e.rotation_error_mean_deg, "%.4g"));
  row("relative rotation error median (deg)", num(e.relative_rotation_error_median_deg, "%.4g"));
  row("pairs (failed)",
      std::to_string(e.num_pairs) + " (" + std::to_string(e.num_failed_pairs) + ")");
  std::string aucs;
  for (size_t k = 0; k < e.auc.size(); ++k) {
    aucs += (k ? "  " : "") + std::string("@") + num(e.auc_thresholds_deg[k], "%g") + ": " +
            num(100.0 * e.auc[k], "%.2f");
  }
  row("AUC (%)", aucs);
  return out.str();
}

}  // namespace ramap
