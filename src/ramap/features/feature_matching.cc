#include "ramap/features/feature_matching.h"

#include <Eigen/Core>
#include <cfloat>
#include <cstring>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/features2d.hpp>
#include <set>

#include "ramap/geometry/camera_projection.h"
#include "ramap/geometry/pair_correspondences.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/scene/image_order.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

cv::Mat AsMat(const Descriptors& descriptors) {
  cv::Mat bytes(static_cast<int>(descriptors.size()), descriptors.num_cols, CV_8U,
                const_cast<uint8_t*>(descriptors.data.data()));
  if (descriptors.num_cols == 32) return bytes;  // binary (ORB): Hamming on the bytes
  cv::Mat floats;
  bytes.convertTo(floats, CV_32F);
  return floats;
}

// The matches that pass the ratio test (nearest < max_ratio * second nearest) and, if asked, the
// cross check (row i of 1 is also the nearest of its match in 2), from the nearest neighbours found
// in one pass over the distance matrix; `ratios` gets nearest / second nearest of each.
template <typename Distance>
std::vector<FeatureMatch> AcceptMatches(const std::vector<int>& best2,
                                        const std::vector<Distance>& first2,
                                        const std::vector<Distance>& second2,
                                        const std::vector<int>& best1,
                                        const FeatureMatchingOptions& options,
                                        std::vector<float>* ratios) {
  std::vector<FeatureMatch> matches;
  for (size_t i = 0; i < best2.size(); ++i) {
    // Passing the test makes second2[i] > 0.
    if (!(first2[i] < options.max_ratio * second2[i])) continue;
    if (options.cross_check && best1[best2[i]] != static_cast<int>(i)) continue;
    matches.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(best2[i])});
    if (ratios != nullptr) ratios->push_back(static_cast<float>(first2[i]) / second2[i]);
  }
  return matches;
}

// Brute-force Hamming matching of 256-bit descriptors in one pass over the distance matrix: the two
// nearest neighbours of every row of 1 (ratio test) and the nearest row of 1 for every row of 2
// (cross check) at once. About 4x faster than two OpenCV knnMatch calls on ORB's 32 bytes.
std::vector<FeatureMatch> MatchBinaryDescriptors(const Descriptors& descriptors1,
                                                 const Descriptors& descriptors2,
                                                 const FeatureMatchingOptions& options,
                                                 std::vector<float>* ratios) {
  const size_t n1 = descriptors1.size(), n2 = descriptors2.size();
  if (n1 == 0 || n2 < 2) return {};
  auto words = [](const Descriptors& d) {
    std::vector<uint64_t> w(d.size() * 4);
    std::memcpy(w.data(), d.data.data(), d.data.size());
    return w;
  };
  const std::vector<uint64_t> w1 = words(descriptors1), w2 = words(descriptors2);
  std::vector<int> best2(n1), first2(n1), second2(n1);
  std::vector<int> best1(n2, -1), best1_distance(n2, 257);
  for (size_t i = 0; i < n1; ++i) {
    const uint64_t* a = &w1[4 * i];
    int first = 257, second = 257, first_j = -1;
    for (size_t j = 0; j < n2; ++j) {
      const uint64_t* b = &w2[4 * j];
      const int d = __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) +
                    __builtin_popcountll(a[2] ^ b[2]) + __builtin_popcountll(a[3] ^ b[3]);
      if (d < first) {
        second = first, first = d, first_j = static_cast<int>(j);
      } else if (d < second) {
        second = d;
      }
      if (d < best1_distance[j]) best1_distance[j] = d, best1[j] = static_cast<int>(i);
    }
    best2[i] = first_j, first2[i] = first, second2[i] = second;
  }
  return AcceptMatches(best2, first2, second2, best1, options, ratios);
}

// The descriptors of an image's `count` largest-scale keypoints (keypoint column 3 is the scale;
// all of them when there is no scale column or fewer keypoints).
Descriptors LargestScaleDescriptors(const Keypoints& keypoints, const Descriptors& descriptors,
                                    int count) {
  const size_t n = std::min(keypoints.size(), descriptors.size());
  if (keypoints.num_cols < 3 || static_cast<int>(n) <= count) return descriptors;
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return keypoints.data[a * keypoints.num_cols + 2] > keypoints.data[b * keypoints.num_cols + 2];
  });
  Descriptors subset;
  subset.num_cols = descriptors.num_cols;
  for (int k = 0; k < count; ++k) {
    const auto row = descriptors.data.begin() + order[k] * descriptors.num_cols;
    subset.data.insert(subset.data.end(), row, row + descriptors.num_cols);
  }
  return subset;
}

// The same single pass for float descriptors (SIFT): squared L2 distances of a block of rows of 1
// against every row of 2 by OpenCV's vectorised batchDistance, the two nearest per row and the
// nearest per column taken from it. Half the work of two knnMatch calls (each direction would
// compute the whole distance matrix again).
std::vector<FeatureMatch> MatchFloatDescriptors(const cv::Mat& d1, const cv::Mat& d2,
                                                const FeatureMatchingOptions& options,
                                                std::vector<float>* ratios) {
  const int n1 = d1.rows, n2 = d2.rows;
  if (n1 == 0 || n2 < 2) return {};
  constexpr int kBlockRows = 256;  // a 256 x 4000 float block (4 MB) stays in cache
  std::vector<int> best2(n1), best1(n2, -1);
  std::vector<float> first2(n1), second2(n1), best1_distance(n2, FLT_MAX);
  cv::Mat distances;
  for (int begin = 0; begin < n1; begin += kBlockRows) {
    const int end = std::min(n1, begin + kBlockRows);
    cv::batchDistance(d1.rowRange(begin, end), d2, distances, CV_32F, cv::noArray(),
                      cv::NORM_L2SQR);
    for (int i = begin; i < end; ++i) {
      const float* row = distances.ptr<float>(i - begin);
      float first = FLT_MAX, second = FLT_MAX;
      int first_j = -1;
      for (int j = 0; j < n2; ++j) {
        const float d = row[j];
        if (d < first) {
          second = first, first = d, first_j = j;
        } else if (d < second) {
          second = d;
        }
        if (d < best1_distance[j]) best1_distance[j] = d, best1[j] = i;
      }
      best2[i] = first_j, first2[i] = std::sqrt(first), second2[i] = std::sqrt(second);
    }
  }
  return AcceptMatches(best2, first2, second2, best1, options, ratios);
}

}  // namespace

MatchingMode MatchingModeFromName(const std::string& name) {
  if (name == "auto") return MatchingMode::kAuto;
  if (name == "sequential") return MatchingMode::kSequential;
  if (name == "exhaustive") return MatchingMode::kExhaustive;
  throw InputError("--Matching.mode", "'" + name + "' is not auto, sequential or exhaustive");
}

std::string MatchingModeName(MatchingMode mode) {
  switch (mode) {
    case MatchingMode::kAuto:
      return "auto";
    case MatchingMode::kSequential:
      return "sequential";
    case MatchingMode::kExhaustive:
      return "exhaustive";
  }
  return "auto";
}

MatchingMode ResolveMatchingMode(const FeatureMatchingOptions& options,
                                 const FeatureDatabase& database) {
  if (options.mode != MatchingMode::kAuto) return options.mode;
  if (static_cast<int>(database.images.size()) <= options.auto_exhaustive_max_images) {
    return MatchingMode::kExhaustive;
  }
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  return LooksSequential(names) ? MatchingMode::kSequential : MatchingMode::kExhaustive;
}

void FeatureMatchingOptions::Check() const {
  CheckOption(overlap >= 1, "--Matching.overlap", ">= 1", overlap);
  CheckOption(max_ratio > 0 && max_ratio <= 1, "--Matching.max_ratio", "in (0, 1]", max_ratio);
  CheckOption(max_error_px > 0, "--Matching.max_error_px", "> 0", max_error_px);
  CheckOption(confidence > 0 && confidence < 1, "--Matching.confidence", "in (0, 1)", confidence);
  CheckOption(min_num_inliers >= 5, "--Matching.min_num_inliers", ">= 5", min_num_inliers);
  CheckOption(auto_exhaustive_max_images >= 0, "--Matching.auto_exhaustive_max_images", ">= 0",
              auto_exhaustive_max_images);
  CheckOption(preemptive_num_features >= 0, "--Matching.preemptive_num_features", ">= 0",
              preemptive_num_features);
  CheckOption(preemptive_min_matches >= 1, "--Matching.preemptive_min_matches", ">= 1",
              preemptive_min_matches);
  CheckOption(num_threads >= 1, "--Matching.num_threads", ">= 1", num_threads);
}

std::vector<FeatureMatch> MatchDescriptors(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const FeatureMatchingOptions& options,
                                           std::vector<float>* ratios) {
  std::vector<FeatureMatch> matches;
  if (ratios != nullptr) ratios->clear();
  if (descriptors1.num_cols != descriptors2.num_cols) return matches;
  if (descriptors1.num_cols == 32)
    return MatchBinaryDescriptors(descriptors1, descriptors2, options, ratios);
  return MatchFloatDescriptors(AsMat(descriptors1), AsMat(descriptors2), options, ratios);
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
  // overlap ran plain RANSAC to its iteration cap and took 54% of the matching time. Measured
  // (templeRing, 1081 pairs): SIFT 43.7 -> 14.1 s, ORB 62.5 -> 18.9 s, with fewer but cleaner
  // verified pairs (the mapper's AUC@1 after BA 70.9 -> 73.7%, ORB 19.8 -> 29.9%); KITTI 07's
  // sequential pairs equal in time and accuracy (ATE after BA: ORB 0.38 -> 0.44%, SIFT 0.51 ->
  // 0.50% of the path).
  cv::Mat mask;
  *E = cv::findEssentialMat(points1, points2, 1.0, cv::Point2d(0, 0), cv::USAC_DEFAULT,
                            options.confidence, options.max_error_px / focal, mask);
  if (E->rows != 3 || E->cols != 3) return cv::Mat();  // none, or several stacked solutions
  cv::Mat pose_mask = mask.clone();
  cv::recoverPose(*E, points1, points2, *R, *t, 1.0, cv::Point2d(0, 0), pose_mask);
  return mask;
}

// The pair's pose by ramap's own estimator on the inliers (grid-selected six points, refined on
// all): OpenCV's minimal-sample E is poorly conditioned through long lenses (templeRing: median
// 8.7 deg, with twisted-pair flips), and COLMAP 3.8 stores no pose at all.
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
  const bool calibrated = camera1.has_prior_focal_length && camera2.has_prior_focal_length;
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

MatchingSummary MatchDatabase(FeatureDatabase* database, const FeatureMatchingOptions& options,
                              std::ostream* progress) {
  options.Check();
  Timer timer;
  const MatchingMode mode = ResolveMatchingMode(options, *database);
  const std::vector<uint32_t> ordered = ImageIdsInCaptureOrder(*database);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t a = 0; a < ordered.size(); ++a) {
    const size_t last = mode == MatchingMode::kExhaustive
                            ? ordered.size()
                            : std::min(ordered.size(), a + 1 + options.overlap);
    for (size_t b = a + 1; b < last; ++b) {
      pairs.emplace_back(std::min(ordered[a], ordered[b]), std::max(ordered[a], ordered[b]));
    }
  }
  const int num_screened = static_cast<int>(pairs.size());
  const bool preemptive = mode == MatchingMode::kExhaustive && options.preemptive_num_features > 0;
  if (preemptive) pairs = ScreenPairsPreemptively(*database, pairs, options, progress);
  database->matches.clear();
  database->two_view_geometries.clear();
  MatchingSummary summary = MatchImagePairs(database, pairs, options, progress);
  if (preemptive) summary.num_preemptive_pairs = num_screened;
  summary.seconds = timer.ElapsedSeconds();
  return summary;
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
