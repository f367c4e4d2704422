#include "ramap/pipeline/relative_poses.h"

#include "ramap/geometry/pair_correspondences.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/util/parallel.h"

namespace ramap {

bool IsUsableTwoViewConfig(TwoViewConfig config) {
  return config == TwoViewConfig::kCalibrated || config == TwoViewConfig::kUncalibrated ||
         config == TwoViewConfig::kPlanar || config == TwoViewConfig::kPlanarOrPanoramic ||
         config == TwoViewConfig::kCalibratedRig;
}

std::vector<ImagePair> EstimateRelativePoses(const FeatureDatabase& database,
                                             const ImageBearings& bearings,
                                             const RelativePoseOptions& options, int num_threads,
                                             std::ostream* progress) {
  std::vector<ImagePair> pairs;
  std::vector<const TwoViewGeometry*> geometries;
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
    geometries.push_back(&geometry);
  }
  // Each pair's correspondences live only while it is estimated.
  ParallelFor(
      pairs.size(), num_threads,
      [&](size_t k) {
        const TwoViewGeometry& geometry = *geometries[k];
        const Camera& camera1 =
            database.cameras.at(database.images.at(geometry.image_id1).camera_id);
        const Camera& camera2 =
            database.cameras.at(database.images.at(geometry.image_id2).camera_id);
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
        ImagePair& pair = pairs[k];
        pair.estimate = EstimateRelativePose(correspondences, options);
        pair.is_inlier.assign(geometry.inlier_matches.size(), false);
        for (const int inlier : pair.estimate.inliers) pair.is_inlier[match_indices[inlier]] = true;
        // Its indices point into the correspondences released here: is_inlier replaces them.
        std::vector<int>().swap(pair.estimate.inliers);
      },
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
