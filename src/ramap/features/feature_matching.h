// Matching and geometric verification of image pairs for image-list input, written as COLMAP's
// matcher writes them (matches and two_view_geometries), so that COLMAP's mapper and ramap's read
// exactly the same data.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "ramap/features/descriptor_matching.h"
#include "ramap/features/image_retrieval.h"
#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

// Which pairs are matched (matching_plan.h).
enum class MatchingMode {
  kAuto,        // exhaustive for small collections; sequential for frame-numbered names; else
                // retrieval
  kSequential,  // a video: each frame with the next `overlap`, plus loop candidates by retrieval
  kExhaustive,  // every pair (screened preemptively)
  kRetrieval,   // each image with its `retrieval_num_neighbors` most similar (screened)
};

// "auto", "sequential", "exhaustive" or "retrieval"; throws InputError naming --Matching.mode
// otherwise.
MatchingMode MatchingModeFromName(const std::string& name);
std::string MatchingModeName(MatchingMode mode);

struct FeatureMatchingOptions {
  MatchingMode mode = MatchingMode::kAuto;
  // Auto mode: exhaustive up to this many images (every overlapping pair is found, whatever the
  // order of the photos, and 50 images are 1225 pairs, about what retrieval's neighbours would
  // cost); beyond it sequential when the names are frame numbers of one sequence, else retrieval.
  int auto_exhaustive_max_images = 50;
  // Sequential mode: each image is matched with the next `overlap` images in capture order
  // (COLMAP's SequentialMatching.overlap default, 10), and with its `loop_num_neighbors` most
  // similar images at least `loop_min_frame_gap` frames away (image retrieval; 0: none), so that
  // a revisit is matched before the mapper runs.
  int overlap = 10;
  int loop_num_neighbors = 2;
  int loop_min_frame_gap = 50;
  // Retrieval mode: each image with its `retrieval_num_neighbors` most similar images.
  int retrieval_num_neighbors = 30;
  ImageRetrievalOptions retrieval;
  // Lowe's ratio test and mutual nearest neighbours (COLMAP's SiftMatching defaults: 0.8, on).
  double max_ratio = 0.8;
  bool cross_check = true;
  // RANSAC on the essential matrix with the cameras' intrinsics: inlier threshold in pixels and
  // confidence (COLMAP's TwoViewGeometry max_error 4 px, confidence 0.999).
  double max_error_px = 4.0;
  double confidence = 0.999;
  // Pairs with fewer inliers get no two-view geometry (COLMAP's min_num_inliers, 15).
  int min_num_inliers = 15;
  // Every pair of exhaustive matching and a video's loop candidates: preemptive matching (Wu,
  // "Towards Linear-time Incremental Structure from Motion", 3DV 2013): the preemptive_num_features
  // largest-scale features of two images are matched first, and only pairs with at least
  // preemptive_min_matches among them are matched in full. Wu's values, 100 and 4. 0 features:
  // every pair in full.
  int preemptive_num_features = 100;
  int preemptive_min_matches = 4;
  int num_threads = 2;
  // Pairs of two cameras with a given focal length are verified with an essential matrix through
  // it; otherwise with a fundamental matrix on the pixels, as pairs of unknown cameras are. Not an
  // option: `ramap reconstruct` clears it unless the user gave --ImageReader.camera_params, so that
  // an EXIF focal length is tested by the mapper against F, never assumed in verification (an E
  // through a focal length 10x off keeps the wrong inliers, and its F confirms the wrong value).
  bool essential_matrix_for_given_focal_lengths = true;

  DescriptorMatchingOptions descriptor_matching() const { return {max_ratio, cross_check}; }
  void Check() const;  // throws InputError naming the option
};

// Its options (--Matching.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<FeatureMatchingOptions>& FeatureMatchingOptionTable();

// Putative matches of two descriptor sets (Hamming distance for 32-byte binary descriptors, L2
// otherwise), after the ratio test and, if asked, the cross check. With `ratios`, also each
// match's nearest / second-nearest distance ratio (its confidence; lower is better).
std::vector<FeatureMatch> MatchDescriptors(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const FeatureMatchingOptions& options,
                                           std::vector<float>* ratios = nullptr);

// The verified geometry of a pair from its putative matches: essential-matrix RANSAC on undistorted
// keypoints (OpenCV), F from E and the intrinsics, cam2_from_cam1 by EstimateRelativePose on the
// inliers (from E when that rejects the pair; unit translation).
// Config kCalibrated with the inliers, or kDegenerate with none when fewer than min_num_inliers
// survive. `ratios` (one per match, or empty) are kept for the inliers (inlier_ratios).
TwoViewGeometry VerifyMatches(uint32_t image_id1, uint32_t image_id2, const Camera& camera1,
                              const Camera& camera2, const Keypoints& keypoints1,
                              const Keypoints& keypoints2, const std::vector<FeatureMatch>& matches,
                              const FeatureMatchingOptions& options,
                              const std::vector<float>& ratios = {});

struct MatchingSummary {
  int num_pairs = 0;           // pairs matched in full
  int num_verified_pairs = 0;  // pairs with a two-view geometry
  double seconds = 0.0;
};

// The pairs worth matching in full: those whose preemptive_num_features largest-scale features
// give at least preemptive_min_matches matches (see FeatureMatchingOptions).
std::vector<std::pair<uint32_t, uint32_t>> ScreenPairsPreemptively(
    const FeatureDatabase& database, const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
    const FeatureMatchingOptions& options, std::ostream* progress = nullptr);

// Matches and verifies the given pairs (image_id1 < image_id2) only, replacing their earlier
// matches and geometries and leaving every other pair as it is (loop candidates, for one).
MatchingSummary MatchImagePairs(FeatureDatabase* database,
                                const std::vector<std::pair<uint32_t, uint32_t>>& pairs,
                                const FeatureMatchingOptions& options,
                                std::ostream* progress = nullptr);

}  // namespace ramap
