// Relative rotation (and translation direction) of an image pair from bearing vectors.
//
// Method (docs/architecture.md, stage 1; "Pushing the Envelope of Rotation Averaging for Visual SLAM", Li,
// Yuan, Latecki, Ling): six well-spread correspondences are chosen with a grid
// (geometry/correspondence_sampling.h), the rotation is solved from them independently of the
// translation with Kneip's rotation-only solvers (L. Kneip, R. Siegwart, M. Pollefeys, "Finding
// the Exact Rotation between Two Images Independently of the Translation", ECCV 2012, as shipped by
// OpenGV), kept only when consistent with the epipolar constraint over the pair's inliers, then
// refined on all inliers by minimising Kneip & Lynen's eigenvalue objective ("Direct Optimization
// of Frame-to-Frame Rotation", ICCV 2013). The translation direction follows from the rotation.
//
// Convention (ramap-wide, COLMAP's): x_cam = R * x_world + t. The edge (i, j) holds
// R_ij = R_j * R_i^T, i.e. the rotation cam_j_from_cam_i, and the unit translation t_ij of
// cam_j_from_cam_i: x_j = R_ij * x_i + lambda * t_ij for some lambda > 0. Here image 1 is i and
// image 2 is j. (OpenGV returns the inverse, camera-2-to-camera-1: f1 ~ R f2 + t.)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "ramap/geometry/correspondence_sampling.h"

namespace ramap {

struct RelativePoseOptions {
  // Pairs with fewer verified matches, or fewer inliers after estimation, are rejected
  // (COLMAP's TwoViewGeometryOptions::min_num_inliers).
  int min_num_inliers = 15;
  // Grid of the paper's selection, the same for both images. 8 x 6 gives roughly square cells on
  // 4:3 images and 48 cells, enough for six well-separated ones (our choice; the paper does not
  // state its grid).
  int grid_cols = 8;
  int grid_rows = 6;
  // Greedy spread of the six grid cells: minimum Chebyshev distance in cells, relaxed to 1 when
  // too few cells remain.
  int min_cell_distance = 2;
  CorrespondenceSampler sampler = CorrespondenceSampler::kGrid;
  // Seeds the random sampler and RANSAC.
  uint64_t seed = 0;
  // Epipolar error (pixels: the angle of a bearing to the epipolar plane times the focal length)
  // above which a match is an outlier; COLMAP's verification threshold (TwoViewGeometryOptions::
  // max_error, 4 px). A threshold in pixels, not radians, keeps long lenses (templeRing: 1520 px)
  // from accepting 12 px errors.
  double max_epipolar_error_px = 4.0;
  // A solved rotation is kept only when at least this fraction of the matches are inliers to it
  // (the paper's epipolar consistency check; ours: verified matches are mostly inliers).
  double min_inlier_ratio = 0.5;
  // Median parallax (pixels) of the matches after the best pure-rotation fit below which the pair
  // is taken as pure rotation / low parallax: flagged, rotation kept, translation zero. Pure
  // rotation with 1 px keypoint noise leaves a median of ~1.2 px (Rayleigh); 2 px is just above.
  // It was 0.5 deg, which on templeRing's narrow field of view (1520 px focal length) took 204 of
  // 329 orbit pairs for rotations and biased their rotations by the orbit angle (median error 12
  // deg): sideways motion seen through a long lens is mostly absorbed by the rotation fit.
  double pure_rotation_parallax_px = 2.0;
  // Median angle between the raw bearings (degrees) below which the images are taken as the same
  // view (duplicate frames, no motion): rejected.
  double min_motion_deg = 0.01;
  // Bearings closer than this (RMS, radians) to one great circle in either image are collinear:
  // the rotation is not determined, rejected.
  double min_bearing_spread = 1e-3;
  // The non-linear refinement uses at most this many inliers (evenly spaced through the match
  // list); the inlier set itself is always re-scored on every match. Pairs of large images carry
  // thousands of matches, and the refinement's cost grows with them while its accuracy stops
  // improving long before.
  int max_refinement_matches = 500;
  // Rank a pair's matches for the grid selection by their descriptor ratio when the database has
  // it (ramap's matcher stores it) instead of their Sampson error under F. Off: measured on
  // ramap-matched databases (scripts/bench_relative_poses.sh), the ratio ties on KITTI 07 (SIFT
  // rotation p90 0.225 vs 0.226 deg, ORB 0.329 vs 0.338) and loses on templeRing (SIFT p90 16.4
  // vs 13.1 deg, ORB median 2.75 vs 2.69): geometric agreement beats descriptor distinctiveness.
  bool use_descriptor_ratios = false;
  // Where the rotation candidates of each five of the six selected matches come from (they guard
  // against one bad match among the six). 0: Kneip's rotation-only five-point solver (ECCV 2012),
  // the paper's solver family. 1: Nister's five-point essential matrices ("An Efficient Solution
  // to the Five-Point Relative Pose Problem", PAMI 2004, as shipped by OpenGV), one rotation per
  // essential matrix: five times cheaper per call (34 vs 177 us), relative poses 1.6x faster on
  // KITTI 07 with per-pair errors as good or better on every real set
  // (scripts/bench_relative_poses.sh), but KITTI 07's averaging alone is worse with it (AUC@3 64 ->
  // 58 with the rotation edge weights, 60 -> 53 without: a few weak far-apart pairs come out a
  // little wrong instead of grossly wrong, and are kept).
  bool nister_five_point = false;
  // The five-point candidates guard against one bad match among the six; with Kneip's solver
  // they were over half of a pair's time. They are solved one leave-one-out subset at a time, and
  // no more subsets are solved once a candidate is confident: it explains at least
  // `confident_inlier_ratio` of the first preemptive round's matches with an RMS epipolar error of
  // those inliers of at most `confident_max_rms_error_px`, in a pair of at least
  // `confident_min_matches` verified matches. That five was then clean, and the other subsets
  // could only add candidates that differ by noise (which the refinement on all inliers removes)
  // or that are worse. A candidate that explains enough matches but misses the error bound is
  // refined on those inliers once before the test: a root solved from five noisy matches has 0.7-
  // 1.1 px RMS on the synthetic drives (0.5 px keypoint noise), their refined fit about 0.65 px.
  // The error bound is what makes the stop safe under long lenses, where the matches span a narrow
  // cone of view directions and wrong roots fit nearly as well as the right one: on templeRing
  // (1520 px focal length, matches spread 3.6-6.9 deg) wrong roots explain 90% of the matches
  // within the 4 px threshold, and pair rotation error p90 went from 5.1 deg (every candidate)
  // to 8.0 with the inlier ratio alone and 7.1 with a 1 px bound after the refinement, and stays
  // 5.0-5.1 with 0.6 px. So views whose first-round matches spread less than
  // `confident_narrow_view_deg` (RMS angle to their mean bearing, in image 1) must meet
  // `confident_narrow_view_rms_error_px`. Measured (scripts/bench_relative_poses.sh, every real
  // set's errors as with every candidate or better): wide bound 0.6 px, 0.8 and 1.0 alike on the
  // real sets; on the synthetic KITTI 06 drive 1.12, 0.69 and 0.65 ms per pair against 1.16 with
  // every candidate, the same pair errors. Weak pairs always get every candidate (with few
  // matches a wrong root can still fit most of them). The all-six eigensolver's candidates may not
  // stop the search: with the same test they took templeRing's p90 to 6.8 deg. Above 1: every
  // candidate, always.
  double confident_inlier_ratio = 0.9;
  double confident_max_rms_error_px = 0.8;
  double confident_narrow_view_deg = 8.0;
  double confident_narrow_view_rms_error_px = 0.6;
  int confident_min_matches = 100;
  // The mapper first estimates this many evenly spaced strong pairs with every candidate and
  // raises confident_max_rms_error_px to what their epipolar errors say the keypoints' noise gives
  // (pipeline/relative_poses.cc; never lowers it); 0: the bound as given.
  int confident_noise_sample = 32;
  // RANSAC (sampler = ransac5): iterations cap and success probability.
  int ransac_max_iterations = 1000;
  double ransac_probability = 0.999;

  // Throws InputError naming the offending option.
  void Check() const;
};

// Estimates cam2_from_cam1 from the matches of one pair. Never throws on degenerate data: bad
// input (fewer than six / min_num_inliers matches, non-finite values, no focal length, all
// keypoints in one grid cell, collinear bearings, no motion) gives success = false and a reason.
RelativePoseEstimate EstimateRelativePose(const TwoViewCorrespondences& matches,
                                          const RelativePoseOptions& options);

// Epipolar error (radians) of one match under (R, t), x2 = R x1 + t: the mean of the angles of
// f2 to the epipolar plane in camera 2 and of f1 to the epipolar plane in camera 1.
double EpipolarError(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Vector3d& f1,
                     const Eigen::Vector3d& f2);

// The unit translation best explaining the matches `indices` under rotation R: the eigenvector of
// the smallest eigenvalue of sum_k n_k n_k^T, n_k = (R f1_k) x f2_k (Kneip & Lynen 2013). Sign
// not fixed. `min_eigenvalue` (optional) receives that eigenvalue, the ICCV 2013 objective.
Eigen::Vector3d TranslationFromRotation(const std::vector<Eigen::Vector3d>& bearings1,
                                        const std::vector<Eigen::Vector3d>& bearings2,
                                        const std::vector<int>& indices, const Eigen::Matrix3d& R,
                                        double* min_eigenvalue = nullptr);

}  // namespace ramap
