// Similarity alignment of estimated camera centres to reference (ground-truth) centres.
//
// The least-squares similarity between two point sets is the closed form of Umeyama, "Least-squares
// estimation of transformation parameters between two point patterns", IEEE TPAMI 13(4), 1991
// (Eigen::umeyama implements it). Without scale the same closed form gives the best rigid
// transform. The robust variant is RANSAC (Fischler & Bolles 1981) over minimal triples followed by
// a least-squares refit on the inliers, in the spirit of `colmap model_aligner --robust_alignment
// 1`.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "ramap/scene/rigid3.h"

namespace ramap {

// A similarity y = scale * R x + t.
struct Sim3d {
  double scale = 1.0;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Sim3d() = default;
  Sim3d(double s, const Eigen::Quaterniond& r, const Eigen::Vector3d& t)
      : scale(s), rotation(r), translation(t) {}

  Eigen::Vector3d operator*(const Eigen::Vector3d& x) const {
    return scale * (rotation * x) + translation;
  }
  Sim3d Inverse() const;
  Eigen::Matrix4d ToMatrix() const;
};

// Pose of a camera after its world is mapped by `new_from_old`: camera coordinates are scaled with
// the world, so the camera centre moves to new_from_old * centre and the rotation becomes
// R_cam * R^T (the convention of COLMAP's Reconstruction::Transform).
Rigid3d TransformPose(const Sim3d& new_from_old, const Rigid3d& cam_from_old);

enum class AlignmentStatus {
  kSuccess,
  kTooFewPoints,      // fewer than 3 correspondences (or source/target sizes differ)
  kCoincidentPoints,  // all source or all target points (almost) identical: no scale, no rotation
  kCollinearPoints,   // source or target points (almost) on one line: rotation about it undefined
  kNoConsensus,       // robust mode: no non-degenerate sample reached 3 inliers
};
const char* AlignmentStatusName(AlignmentStatus status);

struct AlignmentOptions {
  // Sim(3) when true, SE(3) (scale fixed to 1) when false. Default: reconstructions have no scale.
  bool estimate_scale = true;
  // Spread test: points are coincident when their largest singular value (after centring) is at
  // most this times their distance from the origin plus that value, and collinear when the second
  // singular value is at most this times the first. 1e-6 keeps exact degeneracy out while a real
  // trajectory (a car driving straight for a while) still counts as spread.
  double min_spread_ratio = 1e-6;

  // RANSAC over minimal triples, then a refit on the inliers (until the inlier set is stable).
  bool robust = false;
  // Inlier threshold on the aligned centre distance, in target (ground-truth) units. No default can
  // be unit free (as COLMAP's --robust_alignment_max_error); must be > 0 when `robust`.
  double robust_max_error = 0.0;
  // Samples drawn when there are more triples than this; with fewer, every triple is tried.
  int robust_max_iterations = 2000;
  // Refit rounds on the inlier set (each re-selects inliers with the refitted transform).
  int robust_max_refits = 10;
  uint64_t random_seed = 0;  // fixed: the evaluation of a model must be reproducible

  // Throws InputError("AlignmentOptions", ...) on an invalid value.
  void Check() const;
};

struct AlignmentResult {
  AlignmentStatus status = AlignmentStatus::kTooFewPoints;
  Sim3d target_from_source;  // identity unless status == kSuccess
  // Which correspondences the final fit used (all true when not robust and successful).
  std::vector<bool> inliers;
  int num_inliers = 0;

  bool ok() const { return status == AlignmentStatus::kSuccess; }
};

// Finds target_from_source minimising sum ||target_i - T * source_i||^2 (over the inliers when
// robust). Never throws on degenerate data: the status says why there is no transform.
AlignmentResult AlignPoints(const std::vector<Eigen::Vector3d>& source,
                            const std::vector<Eigen::Vector3d>& target,
                            const AlignmentOptions& options = AlignmentOptions());

// The degeneracy test AlignPoints applies to each point set (kSuccess when spread in 3D or in a
// plane, as three non-collinear points fix a similarity).
AlignmentStatus CheckPointSpread(const std::vector<Eigen::Vector3d>& points,
                                 double min_spread_ratio);

}  // namespace ramap
