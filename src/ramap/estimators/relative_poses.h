// Stage 1 of the mapper: the view graph, the relative pose of every verified image pair estimated
// in parallel.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "ramap/estimators/bearings.h"
#include "ramap/geometry/correspondence_sampling.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/io/relative_pose_file.h"
#include "ramap/scene/features.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// Whether COLMAP's verification left a geometry this stage can use (calibrated or uncalibrated
// epipolar geometry, or a planar scene; not degenerate, watermark or pure panorama).
bool IsUsableTwoViewConfig(TwoViewConfig config);

// Every pair of `database.two_view_geometries` with a usable config and at least
// options.min_num_inliers verified matches, estimated on `num_threads` threads. Pairs that fail
// stay in the result with estimate.success == false and the reason. The confidence of a match (for
// the grid selection) is its descriptor ratio when ramap's matcher stored one (and
// options.use_descriptor_ratios), else its Sampson error under the fundamental matrix. With
// `progress`, one line there counts the pairs done in tens of percent.
std::vector<ImagePair> EstimateRelativePoses(const FeatureDatabase& database,
                                             const ImageBearings& bearings,
                                             const RelativePoseOptions& options, int num_threads,
                                             std::ostream* progress = nullptr);

// Why `database` has no pair this stage can use, in the user's terms (for the mapper's error).
std::string WhyNoVerifiedPairs(const FeatureDatabase& database, int min_num_inliers);

// The accepted pairs by image name, as `ramap relative_poses` writes them.
std::vector<RelativePoseRecord> AcceptedRelativePoses(const FeatureDatabase& database,
                                                      const std::vector<ImagePair>& pairs);

}  // namespace ramap
