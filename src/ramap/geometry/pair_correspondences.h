// A verified image pair's matches as the relative-pose estimator takes them. The mapper (with the
// bearings of every keypoint computed once) and the matcher (which estimates each pair's pose
// while it verifies it) assemble them here, so both rank and filter matches alike.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ramap/scene/camera.h"
#include "ramap/scene/features.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// One image of the pair.
struct PairImage {
  const Camera& camera;
  const Keypoints& keypoints;
  // The bearing of every keypoint, when computed already (e.g. through refined intrinsics); else
  // each matched keypoint's bearing is computed through `camera`.
  const std::vector<Eigen::Vector3d>* bearings = nullptr;
};

// The inlier matches of `geometry` between `image1` and `image2`, without those whose keypoint has
// no bearing (past a strong distortion's fold). The match confidence for the grid selection is
// the stored descriptor ratio when `use_descriptor_ratios` and the geometry has ratios, else the
// Sampson error under its fundamental matrix (none when F is zero). `focal_length_px` turns the
// estimator's pixel thresholds into angles. `kept_indices` (optional) receives, for each
// correspondence, the index of its match in geometry.inlier_matches.
TwoViewCorrespondences PairCorrespondences(const PairImage& image1, const PairImage& image2,
                                           const TwoViewGeometry& geometry, double focal_length_px,
                                           bool use_descriptor_ratios,
                                           std::vector<uint32_t>* kept_indices = nullptr);

}  // namespace ramap
