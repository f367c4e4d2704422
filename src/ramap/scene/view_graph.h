// The view graph's pairs: every verified image pair with the matches the mapper reads from it,
// its relative pose (or why it has none) and its weight. The stages after relative poses see the
// accepted ones as a RotationGraph (scene/rotation_graph.h): one edge per accepted pair, each
// edge naming its pair by index.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "ramap/scene/features.h"
#include "ramap/scene/rotation_graph.h"

namespace ramap {

// The verified matches of one image pair, as the relative-pose estimator consumes them.
// Entry k of every vector describes the same match.
struct TwoViewCorrespondences {
  std::vector<Eigen::Vector3d> bearings1;  // unit, undistorted, in camera 1
  std::vector<Eigen::Vector3d> bearings2;  // unit, undistorted, in camera 2
  std::vector<Eigen::Vector2d> pixels1;    // keypoint positions in image 1 (for the grid)
  std::vector<Eigen::Vector2d> pixels2;    // keypoint positions in image 2
  int width1 = 0, height1 = 0;             // image sizes in pixels
  int width2 = 0, height2 = 0;
  // Mean focal length of the two cameras in pixels: turns the estimator's pixel thresholds into
  // angles. 0 (unknown) makes the estimator reject the pair.
  double focal_length_px = 0.0;
  // Per-match confidence, lower is better (e.g. Sampson error or descriptor distance); the caller
  // fills it. Empty means all matches are equally good (ties broken by index).
  std::vector<double> confidence;

  size_t size() const { return bearings1.size(); }
};

// Flags of an accepted edge.
enum RelativePoseFlags : uint32_t {
  kRelativePoseNone = 0,
  // Median parallax after rotation compensation is below pure_rotation_parallax_px: the
  // translation direction is undetermined and set to zero.
  kRelativePosePureRotation = 1u << 0,
};

// Why a pair's relative pose was rejected, by kind (the estimate's `reason` has the numbers).
enum class RelativePoseRejection {
  kNone,                // success
  kInvalidInput,        // inconsistent lengths, sizes, non-finite or zero bearings
  kUnknownFocalLength,  // pixel thresholds cannot become angles
  kTooFewMatches,       // fewer than six / min_num_inliers
  kTooLittleSpread,     // one grid cell, or bearings on one great circle
  kNoMotion,            // identical or duplicate views
  kPureRotationTooFewInliers,
  kNoHypothesis,   // no six correspondences, no solver root, no essential matrix
  kTooFewInliers,  // the hypothesis or its refinement explains too few matches
  kRefinementDiverged,
  kLowInlierRatio,  // below min_inlier_ratio: the paper's consistency check
  kNonFiniteEstimate,
};

// "too few matches", ...: the kind as the relative_poses summary groups it.
const char* RelativePoseRejectionName(RelativePoseRejection rejection);

struct RelativePoseEstimate {
  bool success = false;
  // cam2_from_cam1 (R_ij) and its unit translation (zero when kRelativePosePureRotation).
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  int num_inliers = 0;
  // Indices (into the input) of the inliers of the final estimate.
  std::vector<int> inliers;
  // Median epipolar error of the inliers (radians).
  double median_residual = 0;
  // Median angle between R f1 and f2 over the inliers (degrees).
  double median_parallax_deg = 0;
  // Fraction of inliers in front of both cameras (1 for pure rotation).
  double cheirality_ratio = 0;
  // Leave-one-out five-point subsets solved (six unless a candidate was confident first:
  // RelativePoseOptions::confident_inlier_ratio); 0 without the six-point hypothesis.
  int num_five_point_subsets = 0;
  uint32_t flags = kRelativePoseNone;
  // Why the edge was rejected: the kind, and in words with its numbers (empty on success).
  RelativePoseRejection rejection = RelativePoseRejection::kNone;
  std::string reason;
};

// One verified image pair of the view graph.
struct ImagePair {
  uint32_t image_id1 = 0;  // image_id1 < image_id2, as in the database
  uint32_t image_id2 = 0;
  int num_verified_matches = 0;
  // cam2_from_cam1; estimate.success may be false. Its `inliers` (indices into correspondences
  // that are not kept) are empty: is_inlier holds them.
  RelativePoseEstimate estimate;
  // Which of the pair's verified matches (its two-view geometry's inlier_matches, in order) the
  // estimate explains; the later stages read their bearings (InlierMatches). One bit per match:
  // neither the correspondences (100 bytes per match) nor a copy of the matches (8 bytes, as much
  // as the database's own) are kept, which on long drives were a large share of the mapper's
  // memory (BENCHMARKS.md, "Scale").
  std::vector<bool> is_inlier;

  bool accepted() const { return estimate.success; }
};

// The matches of `geometry` (the pair's two-view geometry) that its estimate explains, in order.
std::vector<FeatureMatch> InlierMatches(const ImagePair& pair, const TwoViewGeometry& geometry);

// The weight of a relative rotation in averaging: its number of inliers (at least 1, for records
// read from a file that gives none).
double RelativeRotationWeight(int num_inliers);

// The accepted pairs as a view graph: one edge per accepted pair (pair_index set), weighted by
// RelativeRotationWeight, over the images they join (in increasing id order).
RotationGraph AcceptedRotationGraph(const std::vector<ImagePair>& pairs);

}  // namespace ramap
