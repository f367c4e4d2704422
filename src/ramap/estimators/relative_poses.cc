#include "ramap/estimators/relative_poses.h"

#include <algorithm>

#include "ramap/estimators/stage_names.h"
#include "ramap/geometry/pair_correspondences.h"
#include "ramap/util/even_subset.h"
#include "ramap/util/parallel.h"
#include "ramap/util/statistics.h"

namespace ramap {

bool IsUsableTwoViewConfig(TwoViewConfig config) {
  return config == TwoViewConfig::kCalibrated || config == TwoViewConfig::kUncalibrated ||
         config == TwoViewConfig::kPlanar || config == TwoViewConfig::kPlanarOrPanoramic ||
         config == TwoViewConfig::kCalibratedRig;
}

namespace {

// The pairs to estimate (verified, with enough inliers, both images with bearings) and their
// geometries.
std::vector<ImagePair> UsablePairs(const FeatureDatabase& database, const ImageBearings& bearings,
                                   const RelativePoseOptions& options,
                                   std::vector<const TwoViewGeometry*>* geometries) {
  std::vector<ImagePair> pairs;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (!IsUsableTwoViewConfig(geometry.config)) continue;
    if (static_cast<int>(geometry.inlier_matches.size()) < options.min_num_inliers) continue;
    if (!bearings.bearings.count(geometry.image_id1) ||
        !bearings.bearings.count(geometry.image_id2))
      continue;
    ImagePair pair;
    pair.image_id1 = geometry.image_id1;
    pair.image_id2 = geometry.image_id2;
    pair.num_verified_matches = static_cast<int>(geometry.inlier_matches.size());
    pairs.push_back(std::move(pair));
    geometries->push_back(&geometry);
  }
  return pairs;
}

// One pair's estimate; its correspondences live only while it is estimated.
void EstimatePair(const FeatureDatabase& database, const ImageBearings& bearings,
                  const TwoViewGeometry& geometry, const RelativePoseOptions& options,
                  ImagePair* pair) {
  const Camera& camera1 = database.cameras.at(database.images.at(geometry.image_id1).camera_id);
  const Camera& camera2 = database.cameras.at(database.images.at(geometry.image_id2).camera_id);
  std::vector<uint32_t> match_indices;
  const TwoViewCorrespondences correspondences =
      PairCorrespondences({camera1, database.keypoints.at(geometry.image_id1),
                           &bearings.bearings.at(geometry.image_id1)},
                          {camera2, database.keypoints.at(geometry.image_id2),
                           &bearings.bearings.at(geometry.image_id2)},
                          geometry,
                          0.5 * (bearings.focal_lengths_px.at(camera1.camera_id) +
                                 bearings.focal_lengths_px.at(camera2.camera_id)),
                          options.use_descriptor_ratios, &match_indices);
  pair->estimate = EstimateRelativePose(correspondences, options);
  pair->is_inlier.assign(geometry.inlier_matches.size(), false);
  for (const int inlier : pair->estimate.inliers) pair->is_inlier[match_indices[inlier]] = true;
  // Its indices point into the correspondences released here: is_inlier replaces them.
  std::vector<int>().swap(pair->estimate.inliers);
}

// The confident stop's error bound for wide views, from the keypoints' noise: the median epipolar
// error (pixels) of evenly spaced pairs estimated with every candidate, as the RMS a refined fit
// has at that noise (1.48 times the median for Gaussian errors) with a quarter's margin, and never
// below the option's value. The option's 0.8 px was chosen at 0.5 px of keypoint noise, just
// above what a refined fit has there; at 0.7 px of noise no fit met it, and every pair solved
// every candidate, at a much higher cost per pair. The bound for narrow views stays as given:
// there it guards against wrong roots, which fit nearly as well as the right one.
double NoiseScaledConfidentBound(const FeatureDatabase& database, const ImageBearings& bearings,
                                 const std::vector<ImagePair>& pairs,
                                 const std::vector<const TwoViewGeometry*>& geometries,
                                 const RelativePoseOptions& options, int num_threads) {
  if (!(options.confident_inlier_ratio <= 1.0) || options.confident_noise_sample == 0) {
    return options.confident_max_rms_error_px;
  }
  std::vector<size_t> strong;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (pairs[k].num_verified_matches >= options.confident_min_matches) strong.push_back(k);
  }
  const std::vector<size_t> sample = EvenSubset(strong, options.confident_noise_sample);
  RelativePoseOptions every_candidate = options;
  every_candidate.confident_inlier_ratio = 2.0;
  std::vector<double> errors_px(sample.size(), -1.0);
  ParallelFor(sample.size(), num_threads, [&](size_t s) {
    ImagePair pair = pairs[sample[s]];
    const TwoViewGeometry& geometry = *geometries[sample[s]];
    EstimatePair(database, bearings, geometry, every_candidate, &pair);
    if (!pair.estimate.success) return;
    const uint32_t camera_id = database.images.at(geometry.image_id1).camera_id;
    errors_px[s] = pair.estimate.median_residual * bearings.focal_lengths_px.at(camera_id);
  });
  errors_px.erase(std::remove(errors_px.begin(), errors_px.end(), -1.0), errors_px.end());
  if (errors_px.empty()) return options.confident_max_rms_error_px;
  return std::max(options.confident_max_rms_error_px, 1.25 * 1.48 * Median(std::move(errors_px)));
}

}  // namespace

std::vector<ImagePair> EstimateRelativePoses(const FeatureDatabase& database,
                                             const ImageBearings& bearings,
                                             const RelativePoseOptions& options, int num_threads,
                                             std::ostream* progress) {
  std::vector<const TwoViewGeometry*> geometries;
  std::vector<ImagePair> pairs = UsablePairs(database, bearings, options, &geometries);
  RelativePoseOptions tuned = options;
  tuned.confident_max_rms_error_px =
      NoiseScaledConfidentBound(database, bearings, pairs, geometries, options, num_threads);
  ParallelFor(
      pairs.size(), num_threads,
      [&](size_t k) { EstimatePair(database, bearings, *geometries[k], tuned, &pairs[k]); },
      progress, stage::kRelativePoses, "pairs");
  return pairs;
}

std::vector<RelativePoseRecord> AcceptedRelativePoses(const FeatureDatabase& database,
                                                      const std::vector<ImagePair>& pairs) {
  std::vector<RelativePoseRecord> records;
  for (const ImagePair& pair : pairs) {
    if (!pair.accepted()) continue;
    records.push_back({database.images.at(pair.image_id1).name,
                       database.images.at(pair.image_id2).name, pair.estimate.rotation,
                       pair.estimate.translation, pair.estimate.num_inliers, pair.estimate.flags});
  }
  return records;
}

std::string WhyNoVerifiedPairs(const FeatureDatabase& database, int min_num_inliers) {
  if (database.two_view_geometries.empty()) {
    return "no image pair has verified matches (two_view_geometries is empty); run a matcher "
           "first";
  }
  int panoramic = 0, unusable = 0, few_inliers = 0;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (geometry.config == TwoViewConfig::kPanoramic) {
      ++panoramic;
    } else if (!IsUsableTwoViewConfig(geometry.config)) {
      ++unusable;
    } else if (static_cast<int>(geometry.inlier_matches.size()) < min_num_inliers) {
      ++few_inliers;
    }
  }
  const size_t total = database.two_view_geometries.size();
  std::string problem = "none of the " + std::to_string(total) + " verified pairs can be used: ";
  if (panoramic > 0) {
    problem += std::to_string(panoramic) +
               " PANORAMIC (pure rotation, as in a panorama: averaging needs the cameras to move "
               "between views), ";
  }
  if (unusable > 0) {
    problem += std::to_string(unusable) + " degenerate, watermark or of unknown geometry, ";
  }
  if (few_inliers > 0) {
    problem += std::to_string(few_inliers) + " with fewer than --RelativePose.min_num_inliers " +
               std::to_string(min_num_inliers) + " inliers, ";
  }
  return problem.substr(0, problem.size() - 2);
}

}  // namespace ramap
