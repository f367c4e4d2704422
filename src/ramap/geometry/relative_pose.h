// Relative rotation (and translation direction) of an image pair from bearing vectors.
//
// Method (docs/architecture.md, stage 1; "Pushing the Envelope of Rotation Averaging for Visual
// SLAM", Li, Yuan, Latecki, Ling): six well-spread correspondences are chosen with a grid
// (geometry/correspondence_sampling.h), the rotation is solved from them independently of the
// translation with Kneip's rotation-only solvers (L. Kneip, R. Siegwart, M. Pollefeys, "Finding the
// Exact Rotation between Two Images Independently of the Translation", ECCV 2012, as shipped by
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
#include "ramap/util/option_table.h"

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
  // As an angle (it was 0.5 deg), the threshold took most of templeRing's orbit pairs, seen
  // through a long lens (1520 px focal length), for rotations and biased their rotations by the
  // orbit angle: sideways motion seen through a long lens is mostly absorbed by the rotation fit.
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
  // it (ramap's matcher stores it) instead of their Sampson error under F. Off: on ramap-matched
  // databases the ratio ties on KITTI 07 and loses on templeRing, as agreement with the pair's
  // geometry picks better samples than descriptor distinctiveness (docs/benchmark-history.md,
  // "Which confidence ranks the grid's matches").
  bool use_descriptor_ratios = false;
  // Where the rotation candidates of each five of the six selected matches come from (they guard
  // against one bad match among the six). 0: Kneip's rotation-only five-point solver (ECCV 2012),
  // the paper's solver family. 1: Nister's five-point essential matrices ("An Efficient Solution
  // to the Five-Point Relative Pose Problem", PAMI 2004, as shipped by OpenGV), one rotation per
  // essential matrix: much cheaper per call, and relative poses quicker with per-pair errors as
  // good or better on every real set, but KITTI 07's averaging alone is worse with it: a few weak
  // far-apart pairs come out a little wrong instead of grossly wrong, and are kept
  // (docs/benchmark-history.md, "Relative poses").
  bool nister_five_point = false;
  // The five-point candidates guard against one bad match among the six; with Kneip's solver
  // they were most of a pair's time. They are solved one leave-one-out subset at a time, and
  // no more subsets are solved once a candidate is confident: it explains at least
  // `confident_inlier_ratio` of the first preemptive round's matches with an RMS epipolar error of
  // those inliers of at most `confident_max_rms_error_px`, in a pair of at least
  // `confident_min_matches` verified matches. That five was then clean, and the other subsets
  // could only add candidates that differ by noise (which the refinement on all inliers removes)
  // or that are worse. A candidate that explains enough matches but misses the error bound is
  // refined on those inliers once before the test: a root solved from five noisy matches fits
  // them worse than the bound, even where their refined fit meets it (the synthetic drives, whose
  // keypoints have 0.5 px of noise), so without the refinement almost no pair would stop.
  // The error bound is what makes the stop safe under long lenses, where the matches span a narrow
  // cone of view directions and wrong roots fit nearly as well as the right one: on templeRing
  // (1520 px focal length, matches spread over a few degrees) wrong roots explain most matches
  // within the 4 px threshold, and the inlier ratio alone, or a looser bound, made its pairs'
  // rotations worse than every candidate does, where the narrow bound keeps them as good. So views
  // whose first-round matches spread less than `confident_narrow_view_deg` (RMS angle to their
  // mean bearing, in image 1) must meet `confident_narrow_view_rms_error_px`. Wide views' bound:
  // a tighter one gives the same errors on the real sets but seldom stops on the synthetic drives,
  // a looser one saves little more time; 0.8 px keeps a margin (docs/benchmark-history.md,
  // "Relative poses").
  // Weak pairs always get every candidate (with few matches a wrong root can still fit most of
  // them). The all-six eigensolver's candidates may not stop the search: with the same test they
  // made templeRing's pairs worse. Above 1: every candidate, always.
  double confident_inlier_ratio = 0.9;
  double confident_max_rms_error_px = 0.8;
  double confident_narrow_view_deg = 8.0;
  double confident_narrow_view_rms_error_px = 0.6;
  int confident_min_matches = 100;
  // The mapper first estimates this many evenly spaced strong pairs with every candidate and
  // raises confident_max_rms_error_px to what their epipolar errors say the keypoints' noise gives
  // (estimators/relative_poses.cc; never lowers it); 0: the bound as given.
  int confident_noise_sample = 32;
  // RANSAC (sampler = ransac5): iterations cap and success probability.
  int ransac_max_iterations = 1000;
  double ransac_probability = 0.999;

  // Throws InputError naming the offending option.
  void Check() const;
};

// Its options (--RelativePose.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<RelativePoseOptions>& RelativePoseOptionTable();

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
