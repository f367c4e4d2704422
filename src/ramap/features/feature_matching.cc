#include "ramap/features/feature_matching.h"

#include <Eigen/Core>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <optional>
#include <set>

#include "ramap/geometry/camera_projection.h"
#include "ramap/geometry/pair_correspondences.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/util/blas_threads.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {

MatchingMode MatchingModeFromName(const std::string& name) {
  if (name == "auto") return MatchingMode::kAuto;
  if (name == "sequential") return MatchingMode::kSequential;
  if (name == "exhaustive") return MatchingMode::kExhaustive;
  if (name == "retrieval") return MatchingMode::kRetrieval;
  throw InputError("--Matching.mode",
                   "'" + name + "' is not auto, sequential, exhaustive or retrieval");
}

std::string MatchingModeName(MatchingMode mode) {
  switch (mode) {
    case MatchingMode::kAuto:
      return "auto";
    case MatchingMode::kSequential:
      return "sequential";
    case MatchingMode::kExhaustive:
      return "exhaustive";
    case MatchingMode::kRetrieval:
      return "retrieval";
  }
  return "auto";
}

void FeatureMatchingOptions::Check() const {
  CheckOptionValues(FeatureMatchingOptionTable(), *this);
}

std::vector<FeatureMatch> MatchDescriptors(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const FeatureMatchingOptions& options,
                                           std::vector<float>* ratios) {
  return MatchDescriptors(descriptors1, descriptors2, options.descriptor_matching(), ratios);
}

namespace {

// F on the pixels of `matches` (OpenCV USAC); the inlier mask, empty when there is no F.
cv::Mat FundamentalInlierMask(const std::vector<FeatureMatch>& matches, const Keypoints& keypoints1,
                              const Keypoints& keypoints2, const FeatureMatchingOptions& options,
                              Eigen::Matrix3d* F) {
  std::vector<cv::Point2d> pixels1, pixels2;
  for (const FeatureMatch& match : matches) {
    const Eigen::Vector2d xy1 = keypoints1.xy(match.point2D_idx1);
    const Eigen::Vector2d xy2 = keypoints2.xy(match.point2D_idx2);
    pixels1.emplace_back(xy1.x(), xy1.y());
    pixels2.emplace_back(xy2.x(), xy2.y());
  }
  cv::Mat mask;
  const cv::Mat estimate = cv::findFundamentalMat(pixels1, pixels2, cv::USAC_DEFAULT,
                                                  options.max_error_px, options.confidence, mask);
  if (estimate.rows != 3 || estimate.cols != 3) return cv::Mat();
  cv::cv2eigen(estimate, *F);
  return mask;
}

// E on undistorted normalised coordinates, and the pose it gives; the inlier mask, empty when
// there is no single E.
cv::Mat EssentialInlierMask(const std::vector<cv::Point2d>& points1,
                            const std::vector<cv::Point2d>& points2, double focal,
                            const FeatureMatchingOptions& options, cv::Mat* E, cv::Mat* R,
                            cv::Mat* t) {
  // OpenCV's USAC (Ivashechkin, Barath, Matas, "USAC: a universal framework for random sample
  // consensus", 2021) rather than its plain RANSAC: the pairs of an exhaustive match that do not
  // overlap ran plain RANSAC to its iteration cap and took most of the matching time. USAC
  // matches an unordered collection in a fraction of the time, with fewer but cleaner verified
  // pairs and a more accurate model; a sequence's pairs, which overlap, cost and score the same.
  cv::Mat mask;
  *E = cv::findEssentialMat(points1, points2, 1.0, cv::Point2d(0, 0), cv::USAC_DEFAULT,
                            options.confidence, options.max_error_px / focal, mask);
  if (E->rows != 3 || E->cols != 3) return cv::Mat();  // none, or several stacked solutions
  cv::Mat pose_mask = mask.clone();
  cv::recoverPose(*E, points1, points2, *R, *t, 1.0, cv::Point2d(0, 0), pose_mask);
  return mask;
}

// The pair's pose by ramap's own estimator on the inliers (grid-selected six points, refined on
// all): OpenCV's minimal-sample E is poorly conditioned through long lenses (on templeRing its
// rotations are degrees off, with twisted-pair flips), and COLMAP 3.8 stores no pose at all.
RelativePoseEstimate GridPairPose(const Camera& camera1, const Camera& camera2,
                                  const Keypoints& keypoints1, const Keypoints& keypoints2,
                                  const TwoViewGeometry& geometry, double focal) {
  // Matches ranked and estimated as the mapper does with its default options.
  const RelativePoseOptions options;
  return EstimateRelativePose(PairCorrespondences({camera1, keypoints1}, {camera2, keypoints2},
                                                  geometry, focal, options.use_descriptor_ratios),
                              options);
}

}  // namespace

TwoViewGeometry VerifyMatches(uint32_t image_id1, uint32_t image_id2, const Camera& camera1,
                              const Camera& camera2, const Keypoints& keypoints1,
                              const Keypoints& keypoints2, const std::vector<FeatureMatch>& matches,
                              const FeatureMatchingOptions& options,
                              const std::vector<float>& ratios) {
  const bool has_ratios = !ratios.empty() && ratios.size() == matches.size();
  TwoViewGeometry geometry;
  geometry.image_id1 = image_id1;
  geometry.image_id2 = image_id2;
  geometry.config = TwoViewConfig::kDegenerate;
  if (static_cast<int>(matches.size()) < options.min_num_inliers) return geometry;
  // Undistorted normalised coordinates, so that E is estimated with the intrinsics known.
  std::vector<cv::Point2d> points1, points2;
  std::vector<FeatureMatch> usable;
  std::vector<float> usable_ratios;
  for (size_t k = 0; k < matches.size(); ++k) {
    const FeatureMatch& match = matches[k];
    const Eigen::Vector3d b1 = PixelToBearing(camera1, keypoints1.xy(match.point2D_idx1));
    const Eigen::Vector3d b2 = PixelToBearing(camera2, keypoints2.xy(match.point2D_idx2));
    if (!b1.allFinite() || !b2.allFinite() || b1.z() <= 0 || b2.z() <= 0) continue;
    points1.emplace_back(b1.x() / b1.z(), b1.y() / b1.z());
    points2.emplace_back(b2.x() / b2.z(), b2.y() / b2.z());
    usable.push_back(match);
    if (has_ratios) usable_ratios.push_back(ratios[k]);
  }
  if (static_cast<int>(usable.size()) < options.min_num_inliers) return geometry;
  const double focal = 0.5 * (MeanFocalLength(camera1) + MeanFocalLength(camera2));
  // Without a known focal length (COLMAP's prior_focal_length 0) the essential matrix would hold
  // the guess as truth: estimate F on the pixels instead, as COLMAP does for such pairs, so that
  // the mapper's view-graph calibration can estimate the focal length from it.
  const bool calibrated = options.essential_matrix_for_given_focal_lengths &&
                          camera1.has_prior_focal_length && camera2.has_prior_focal_length;
  cv::Mat E, R, t;
  const cv::Mat mask =
      calibrated ? EssentialInlierMask(points1, points2, focal, options, &E, &R, &t)
                 : FundamentalInlierMask(usable, keypoints1, keypoints2, options, &geometry.F);
  if (mask.empty()) return geometry;
  for (size_t k = 0; k < usable.size(); ++k) {
    if (!mask.at<uchar>(static_cast<int>(k))) continue;
    geometry.inlier_matches.push_back(usable[k]);
    if (has_ratios) geometry.inlier_ratios.push_back(usable_ratios[k]);
  }
  if (static_cast<int>(geometry.inlier_matches.size()) < options.min_num_inliers) {
    geometry.inlier_matches.clear();
    geometry.inlier_ratios.clear();
    return geometry;
  }
  if (calibrated) {
    geometry.config = TwoViewConfig::kCalibrated;
    cv::cv2eigen(E, geometry.E);
    const Eigen::Matrix3d K1 = CalibrationMatrix(camera1), K2 = CalibrationMatrix(camera2);
    geometry.F = K2.inverse().transpose() * geometry.E * K1.inverse();
  } else {
    geometry.config = TwoViewConfig::kUncalibrated;
  }
  const RelativePoseEstimate estimate =
      GridPairPose(camera1, camera2, keypoints1, keypoints2, geometry, focal);
  if (estimate.success) {
    geometry.cam2_from_cam1 = Rigid3d(estimate.rotation, estimate.translation);
  } else if (calibrated) {
    Eigen::Matrix3d rotation;
    Eigen::Vector3d translation;
    cv::cv2eigen(R, rotation);
    cv::cv2eigen(t, translation);
    geometry.cam2_from_cam1 = Rigid3d(Eigen::Quaterniond(rotation), translation.normalized());
  }
  return geometry;
}

std::vector<std::pair<uint32_t, uint32_t>> ScreenPairsPreemptively(
    const FeatureDatabase& database, const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
    const FeatureMatchingOptions& options, std::ostream* progress) {
  std::set<uint32_t> images;
  for (const auto& [id1, id2] : pairs) images.insert({id1, id2});
  std::map<uint32_t, Descriptors> top;
  for (const uint32_t id : images) {
    const auto keypoints = database.keypoints.find(id);
    const auto descriptors = database.descriptors.find(id);
    if (keypoints == database.keypoints.end() || descriptors == database.descriptors.end())
      continue;
    top[id] = LargestScaleDescriptors(keypoints->second, descriptors->second,
                                      options.preemptive_num_features);
  }
  std::vector<char> keep(pairs.size(), 0);
  std::optional<SingleBlasThread> single_blas_thread;
  if (options.num_threads > 1) single_blas_thread.emplace();
  ParallelFor(
      pairs.size(), options.num_threads,
      [&](size_t k) {
        const auto one = top.find(pairs[k].first), two = top.find(pairs[k].second);
        // An image without descriptors is reported by the full matching.
        keep[k] = one == top.end() || two == top.end() ||
                  static_cast<int>(MatchDescriptors(one->second, two->second, options).size()) >=
                      options.preemptive_min_matches;
      },
      progress, "preemptive matching", "pairs");
  std::vector<std::pair<uint32_t, uint32_t>> kept;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (keep[k]) kept.push_back(pairs[k]);
  }
  return kept;
}

MatchingSummary MatchImagePairs(FeatureDatabase* database,
                                const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                const FeatureMatchingOptions& options, std::ostream* progress) {
  options.Check();
  Timer timer;
  const std::string source = database->source_path.empty() ? "database" : database->source_path;
  for (const auto& [id1, id2] : pairs) {
    for (const uint32_t id : {id1, id2}) {
      if (!database->images.count(id)) {
        throw InputError(source, "no image " + std::to_string(id) + " to match");
      }
      if (!database->descriptors.count(id) || !database->keypoints.count(id)) {
        throw InputError(source, "image " + database->images.at(id).name +
                                     " has no keypoints or descriptors: run feature_extractor");
      }
    }
  }
  std::vector<std::vector<FeatureMatch>> matches(pairs.size());
  std::vector<std::vector<float>> ratios(pairs.size());
  std::vector<TwoViewGeometry> geometries(pairs.size());
  // Pairs run in parallel; each one's matrix products on one BLAS thread.
  std::optional<SingleBlasThread> single_blas_thread;
  if (options.num_threads > 1) single_blas_thread.emplace();
  ParallelFor(
      pairs.size(), options.num_threads,
      [&](size_t k) {
        const auto [id1, id2] = pairs[k];
        matches[k] = MatchDescriptors(database->descriptors.at(id1), database->descriptors.at(id2),
                                      options, &ratios[k]);
        const Image& image1 = database->images.at(id1);
        const Image& image2 = database->images.at(id2);
        geometries[k] =
            VerifyMatches(id1, id2, database->cameras.at(image1.camera_id),
                          database->cameras.at(image2.camera_id), database->keypoints.at(id1),
                          database->keypoints.at(id2), matches[k], options, ratios[k]);
      },
      progress, "matching", "pairs");
  MatchingSummary summary;
  summary.num_pairs = static_cast<int>(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const uint64_t pair_id = ImagePairToPairId(pairs[k].first, pairs[k].second);
    database->matches.erase(pair_id);
    database->two_view_geometries.erase(pair_id);
    if (!matches[k].empty()) database->matches[pair_id] = std::move(matches[k]);
    if (!geometries[k].inlier_matches.empty()) {
      database->two_view_geometries[pair_id] = std::move(geometries[k]);
      ++summary.num_verified_pairs;
    }
  }
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
