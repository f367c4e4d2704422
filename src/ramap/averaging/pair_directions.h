// Translation directions of image pairs re-estimated with the averaged (global) rotations fixed.
//
// With both rotations known, the baseline c2 - c1 of a pair is coplanar with every pair of matched
// world rays (d1, d2), so it is the null vector of the stacked normals d1 x d2; this is the
// rotation-known form of the epipolar constraint (cf. Kneip & Lynen 2013, who use the same
// eigenvalues). Re-estimating with global rotations removes the error that the pair's own
// rotation estimate left in its translation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "ramap/util/option_table.h"

namespace ramap {

struct PairDirectionOptions {
  // Rays of a match closer than this carry no direction information (far points); paper-free
  // default.
  double min_ray_angle_deg = 0.5;
  // Reweighting rounds (Cauchy on the coplanarity residual) to resist wrong matches.
  int num_reweighting_rounds = 5;
  // Cauchy scale of the coplanarity residual, in degrees.
  double residual_scale_deg = 0.5;
  // Fewer usable matches than this: no direction (COLMAP's min_num_inliers is 15).
  int min_num_matches = 15;
  // Fraction of matches whose triangulated point must lie in front of both cameras to accept the
  // sign.
  double min_cheirality_ratio = 0.7;
  // A pair's direction is estimated from at most this many of its inlier matches, evenly spaced
  // through them (0: all); the caller picks them (EvenSubset), as it gathers their bearings. A
  // direction is 3 numbers, and the reweighting rounds over every inlier of the synthetic drives'
  // pairs (hundreds each) were the translation stage's largest cost: 256 take much less time at
  // the same accuracy or better, and fewer were no better (BENCHMARKS.md, "Scale").
  int max_num_matches = 256;
  // When fewer than this share of the matches agree with the reweighted direction (coplanarity
  // residual within residual_scale_deg), the rounds start again from the best of
  // num_sampled_starts two-match directions, and the direction more matches agree with is kept.
  // With 10% of random matches the plain start fails and the restart recovers it
  // (tests/averaging/translation_averaging_test.cc). Off (0) by default: the agreement test does
  // not know a pair's parallax: 0.5 restarts many low-parallax pairs of the synthetic drives and
  // moves the drives' accuracy either way (BENCHMARKS.md, "Scale"). 0.5 is the share to try on
  // matches with many wrong ones.
  double min_agreeing_share = 0.0;
  // Two-match directions tried by the restart: with 30% wrong matches, each sample holds one with
  // probability 0.51, all 32 with 4e-10 (were they drawn at random).
  int num_sampled_starts = 32;

  void Check() const;
};

// Its options (--PairDirection.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<PairDirectionOptions>& PairDirectionOptionTable();

// World-frame unit direction of c2 - c1 from the pair's matched bearings (camera frames) and the
// cam_from_world rotations; empty when the pair has too few informative matches or an ambiguous
// sign (pure rotation, all points at infinity).
std::optional<Eigen::Vector3d> EstimatePairDirection(
    const Eigen::Quaterniond& rotation1, const Eigen::Quaterniond& rotation2,
    const std::vector<Eigen::Vector3d>& bearings1, const std::vector<Eigen::Vector3d>& bearings2,
    const PairDirectionOptions& options = PairDirectionOptions());

}  // namespace ramap
