// Camera positions from fixed rotations, pair directions and feature tracks.
//
// Method: Cui, Jiang, Tan, "Linear Global Translation Estimation with Feature Tracks" (BMVC 2015).
// For a track point X seen from cameras a and b, the triangle (c_a, c_b, X) is known up to scale
// once rotations and the pair direction are known, so X = c_a + M_ab (c_b - c_a) with M_ab a
// known scaled rotation (law of sines). Every other camera k of the track predicts the same X
// from its own pair, which gives linear equations in the camera centres only. Unlike pairwise
// direction constraints, these fix the relative baseline lengths along the track, so collinear and
// forward motion is not degenerate.
//
// Pair directions add rows c_j - c_i = s_ij d_ij with one scale s_ij >= 1 per pair (the
// "least unsquared deviations" constraint of Ozyesil & Singer, CVPR 2015). The homogeneous track
// system alone admits collapsed solutions (many cameras on one point, which satisfies every track
// among them); the bound excludes them, fixes the scale and makes the problem convex.
//
// The stacked system is solved in the L1 sense, min ||B v||_1 over v = (centres, scales) with the
// scales >= 1 and one camera held at the origin, started from the least-squares solution with
// every scale at 1: by default by iteratively reweighted least squares (one sparse solve per step:
// a Cholesky factorisation, or conjugate gradients preconditioned with the last one), or by ADMM
// (Boyd et al., "Distributed Optimization and Statistical Learning via ADMM", 2011; the bound is a
// projection), the design's solver, whose long tail on sequences makes it slower and, stopped by
// its tolerances, less accurate (KITTI 07: 7.1 s and ATE 2.7% of the path, against IRLS's 1.1 s
// and 1.9%). The result is then scaled so that the mean projected baseline of the pairs is one.
//
// Position priors (GPS, in a frame the rotations are already aligned to) add rows W (c_i - p_i)
// with W the prior's square-root information, Huber-weighted in IRLS. They fix the gauge (no
// camera is held, the result is not rescaled) and bound drift along a sequence the way a loop
// would; the pair scales then only need s_ij >= 0.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/graph/tracks.h"
#include "ramap/scene/features.h"

namespace ramap {

// World-frame unit direction of c2 - c1 for an image pair.
struct PairDirection {
  uint32_t image_id1 = 0;
  uint32_t image_id2 = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};

// A camera centre measured in the world frame of the rotations: rows
// prior_weight * sqrt_information * (c - center), residuals in standard deviations.
struct CenterPrior {
  uint32_t image_id = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sqrt_information = Eigen::Matrix3d::Identity();
};

enum class TranslationSolver {
  kIrls,  // iteratively reweighted least squares, one direct solve per step (default)
  kAdmm,  // ADMM (Boyd et al. 2011), the design's solver: cheap steps, a long tail on sequences
};

struct TranslationAveragingOptions {
  // Rays meeting at less than this give ill-conditioned depth ratios. Measured on the default
  // synthetic forward-motion scene (ramap synthesize): 3 deg left the last 7 of 30 frames without a
  // constraint (they see only far points); 1.5, 1 and 0.5 deg registered all 30 with AUC@1 92.1,
  // 92.3 and 92.5 %. 1 deg keeps a margin against far-point noise on real data.
  double min_triangulation_angle_deg = 1.0;
  // Observations used per track (the best-conditioned ones); bounds the cost of long tracks.
  int max_observations_per_track = 8;
  // Tracks used at most (the longest first); constraints grow linearly with it.
  int max_num_tracks = 5000;
  // Past max_num_tracks, tracks are still used (longest first) while one of their cameras has
  // fewer than this many: a per-image quota, so that a long drive gets tracks everywhere (the
  // longest tracks cluster on slow stretches and revisits). 0: the global cap alone. Measured
  // (averaging alone): synthetic KITTI 06 drive (scripts/bench_scale.sh) ATE 0.75% of the path
  // at 0, 0.49% at 10, 0.36% at 30, 0.29% at 60 (translation averaging 13 -> 17 -> 16 s);
  // kitti07_first160 AUC@3 58.0 -> 60.2 and ATE 1.86 -> 1.55 m at 30 (with BA: AUC@3 79.9 ->
  // 80.0; from unknown intrinsics, with BA 58.7 -> 59.1 but averaging alone 49.4 -> 49.6 with
  // ATE 2.08 -> 2.42 m); the other benchmark sets stay below the cap and unchanged.
  int min_tracks_per_image = 30;
  // Weight of a pair row (c_j - c_i = s_ij d_ij, residual in position units) against a track row
  // (residual in baselines). The tracks are what carries the scale along a sequence: pair
  // directions on a straight stretch leave it free, and their bounds s_ij >= 1 pull a stretch
  // that only a few tracks tie to the rest to its own scale. It was 10: the 2000-frame KITTI 00
  // drive of scripts/bench_scale.sh then came out 2.4 times too large past frame 1650, where it
  // leaves the looped part (ATE 40 m; with 1: 14 m), and kitti07_first160's averaging alone had
  // AUC@3 62.8 (with 1: 80.6; ATE 1.84 -> 0.49 m). 3 changes little (63.5).
  double pair_constraint_weight = 1.0;
  // Prior rows' weight: 1 makes a one-sigma GPS error cost as much as a baseline in a pair row.
  // Measured with pair rows of weight 1 (GeoregistrationRealData.Kitti07FromNoisyGpsToMetricModel,
  // metric ATE from 3.5 m GPS noise): 0.63 m at 1 (0.65 m with the earlier pair weight 10), 2.77 m
  // at 0.3, 0.79 m at 3.
  double prior_weight = 1.0;
  // IRLS treats prior residuals up to this many standard deviations as squares, beyond as L1
  // (Huber), so that noise averages out and a wrong fix pulls with bounded force.
  double prior_huber_sigmas = 1.0;
  TranslationSolver solver = TranslationSolver::kIrls;
  // IRLS: steps at most; stop when the positions change by less than irls_tolerance (relative);
  // residual floor of the weights 1 / max(|r|, irls_min_residual) (scales are >= 1, so positions
  // are in units of at least the shortest baseline and 1e-4 is far below any real residual).
  // Measured on the benchmark sets: 20 steps already give their final ATE to 3 digits (KITTI 07:
  // 1.87% of the path at 20, 1.91% at 40 and 100 steps).
  int max_irls_iterations = 50;
  double irls_tolerance = 1e-5;
  // IRLS also stops when a step that moved under 1% of the pair scales between held and free
  // lowered its objective (the sum of block residual norms, smoothed below the floor) by less than
  // this fraction of the objective's excess over its least value; the better iterate is kept.
  // Off by default: it halves the steps on long drives at no cost there, but the one real
  // sequence converges slowly and loses by it. Measured (averaging alone): the synthetic drives of
  // scripts/bench_scale.sh stop after 25 (1101-frame KITTI 06) and 24 steps (4541-frame KITTI 00)
  // instead of 50, ATE 0.352% and 0.111% of the path (0.358% and 0.111% after 50); but
  // kitti07_first160's ATE goes from 1.55 m to 1.93 m at 1e-3, 1.66 m at 1e-4 (31 steps) and
  // 1.57 m at 1e-5 (43 steps). 0: the steps stop on irls_tolerance or the cap alone.
  double irls_cost_tolerance = 0;
  // After the solve, pair rows whose direction the solution misses by more than
  // rejection_multiplier times the median miss (at least rejection_min_angle_deg), and track
  // constraints whose residual exceeds rejection_multiplier times the median residual, are removed
  // and the system solved again, at most max_rejection_rounds times (0: never). The threshold
  // follows each system's own residuals (a window's, a component's) rather than a fixed angle.
  int max_rejection_rounds = 1;
  double rejection_multiplier = 5.0;
  double rejection_min_angle_deg = 2.0;
  double irls_min_residual = 1e-4;
  // IRLS step extrapolation: the step to the reweighted solution is taken this many times over
  // (scales projected onto their bound) when that lowers the objective more than the plain step
  // (a safeguarded over-relaxation of the majorise-minimise iteration); 1: plain IRLS. IRLS's slow
  // mode on sequences is the scale drifting along them, which plain steps undo a little at a time.
  // Measured (averaging alone, steps until the positions stop moving): kitti07_first160 67 steps
  // plain (50 by the cap, ATE 1.553 m; 1.546 m converged), 37 at 2, 29 at 2.5 and 31 at 3 (ATE
  // 1.546 m); synthetic drives (scripts/bench_scale.sh) 50 -> 28 steps on KITTI 06 and 50 -> 29 at
  // 4541 frames of KITTI 00 (translation averaging 23.3 -> 18.0 s), ATE unchanged (0.36%, 0.11%).
  double irls_extrapolation = 2.5;
  // Each IRLS step first solves its camera system by conjugate gradients preconditioned with the
  // last Cholesky factor and started at the last solution, and refactorises only when that does
  // not reach a residual of pcg_tolerance times the right-hand side's within max_pcg_iterations
  // (forecast from the rate of the first three iterations: early steps reweight much and give up
  // at once). Late steps reweight little and converge in ~20 iterations; an iteration costs a
  // fortieth of a refactorisation on the 4541-frame drive (whose factor has 6 million entries).
  // 0: refactorise at every step. Measured (scripts/bench_scale.sh, averaging alone): KITTI 06
  // drive 39 -> 13 factorisations, translation averaging 2.7 -> 2.3 s; 4541 frames of KITTI 00
  // 36 -> 17, 14.0 -> 12.5 s (solves 8.6 -> 7.5 s); ATE unchanged (0.20%, 0.03%). A cap of 20
  // without the forecast: 17 factorisations at 4541 frames but 3.1 s in abandoned iterations.
  int max_pcg_iterations = 40;
  double pcg_tolerance = 1e-8;
  // ADMM penalty parameter, the starting value. The sphere makes the splitting nonconvex, which
  // needs rho large enough not to oscillate; with admm_adaptive_rho it is then balanced against
  // the residuals as the iterations go.
  double admm_rho = 10.0;
  // Residual balancing: rho doubled or halved whenever the primal and dual residuals differ by
  // more than 10x (Boyd et al. 2011, sec. 3.4.1).
  bool admm_adaptive_rho = true;
  // Over-relaxation factor (Boyd et al. recommend 1.5 - 1.8).
  double admm_relaxation = 1.6;
  int max_admm_iterations = 2000;
  // Stop when primal and dual residual norms fall below admm_tolerance * sqrt(size) plus
  // admm_relative_tolerance times the size of the iterates (Boyd et al. 2011, sec. 3.3.1).
  double admm_tolerance = 1e-7;
  double admm_relative_tolerance = 1e-4;
  // Also stop when the L1 cost changes by less than this fraction over 50 iterations. Measured on
  // a noisy synthetic ring (30 cameras, 0.1 deg noise): 350 iterations instead of 2000, centres
  // within 7e-5 of the scene size of the 2000-iteration result.
  double admm_cost_tolerance = 1e-5;

  void Check() const;
};

// A pair row that translation averaging dropped as an outlier (TranslationAveragingOptions::
// max_rejection_rounds): the angle by which its solution missed the pair's direction.
struct RejectedPairRow {
  uint32_t image_id1 = 0;
  uint32_t image_id2 = 0;
  double miss_deg = 0.0;
  double threshold_deg = 0.0;
};

struct TranslationAveragingResult {
  // Camera centres in world coordinates (the gauge: `gauge_image_id` at the origin, mean projected
  // pair baseline = 1; with priors, theirs).
  std::map<uint32_t, Eigen::Vector3d> centers;
  uint32_t gauge_image_id = 0;
  // Images with rotations but no usable constraint, not positioned.
  std::vector<uint32_t> unconstrained_images;
  int num_tracks_used = 0;
  int num_constraints = 0;  // 3-row blocks: track constraints and pair rows
  int num_solver_iterations = 0;
  int num_factorizations = 0;  // of the camera system (the others reused one: max_pcg_iterations)
  int num_priors_used = 0;
  int num_windows = 0;  // solved in this many windows (windowed_translation_averaging.h); 0: one
  int num_rejected_rows = 0;  // pair rows and track constraints removed as outliers
  std::vector<RejectedPairRow> rejected_pair_rows;  // the pair rows among them
  double l1_cost = 0.0;
  double seconds = 0.0;
};

// Positions for the cameras of `rotations` (cam_from_world), from the pair directions and the
// feature tracks, whose keypoints' rays are looked up in `bearings` (a track's observations by
// images without a rotation are not used). Cameras linked by no constraint are listed in
// `unconstrained_images`. `priors` of cameras that get positioned are used (see above). Throws
// StageFailure (util/error.h) when fewer than two cameras can be positioned.
TranslationAveragingResult AverageTranslations(
    const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<PairDirection>& pair_directions, const std::vector<Track>& tracks,
    const KeypointBearings& bearings,
    const TranslationAveragingOptions& options = TranslationAveragingOptions(),
    const std::vector<CenterPrior>& priors = {});

}  // namespace ramap
