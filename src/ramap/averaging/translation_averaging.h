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
// projection), whose long tail on sequences makes it slower and, stopped by its tolerances, less
// accurate (BENCHMARKS.md, "Scale"). The result is then scaled so that the mean projected baseline
// of the pairs is one.
//
// Pose priors (GPS, in a frame the rotations are already aligned to) add rows W (c_i - p_i)
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
#include "ramap/util/option_table.h"

namespace ramap {

// World-frame unit direction of c2 - c1 for an image pair.
struct PairDirection {
  uint32_t image_id1 = 0;
  uint32_t image_id2 = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};

// A pose prior (a measured camera centre) in the world frame of the rotations: rows
// prior_weight * sqrt_information * (c - center), residuals in standard deviations.
struct PosePriorInModel {
  uint32_t image_id = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sqrt_information = Eigen::Matrix3d::Identity();
};

enum class TranslationSolver {
  kIrls,  // iteratively reweighted least squares, one direct solve per step (default)
  kAdmm,  // ADMM (Boyd et al. 2011): cheap steps, a long tail on sequences
};

struct TranslationAveragingOptions {
  // Rays meeting at less than this give ill-conditioned depth ratios. A bound as large as 3 deg
  // leaves the last frames of a forward-moving sequence, which see only far points, without a
  // constraint (the default scene of `ramap synthesize`); below 1.5 deg every frame is placed and
  // the accuracy hardly moves. 1 deg keeps a margin against far-point noise on real data.
  double min_triangulation_angle_deg = 1.0;
  // Observations used per track (the best-conditioned ones); bounds the cost of long tracks.
  int max_observations_per_track = 8;
  // Tracks used at most (the longest first); constraints grow linearly with it.
  int max_num_tracks = 5000;
  // Past max_num_tracks, tracks are still used (longest first) while one of their cameras has
  // fewer than this many: a per-image quota, so that a long drive gets tracks everywhere (the
  // longest tracks cluster on slow stretches and revisits). 0: the global cap alone. The quota
  // lowers the drift of long drives for a little more time, and sets whose tracks stay below the
  // cap are unchanged (BENCHMARKS.md, "Scale").
  int min_tracks_per_image = 30;
  // Weight of a pair row (c_j - c_i = s_ij d_ij, residual in position units) against a track row
  // (residual in baselines). The tracks are what carries the scale along a sequence: pair
  // directions on a straight stretch leave it free, and their bounds s_ij >= 1 pull a stretch
  // that only a few tracks tie to the rest to its own scale. A heavier weight let a long drive
  // come out too large past where it leaves its looped part, and cost the real sequence much of
  // its accuracy without bundle adjustment (docs/benchmark-history.md, "2026-12-07, commit
  // ed68479: robustness").
  double pair_constraint_weight = 1.0;
  // Prior rows' weight: 1 makes a one-sigma GPS error cost as much as a baseline in a pair row.
  // Lighter priors no longer bound the drift along a sequence; heavier ones pull the model toward
  // the GPS noise (PriorAlignmentRealData.Kitti07FromNoisyGpsToMetricModel is the case to try).
  double prior_weight = 1.0;
  // IRLS treats prior residuals up to this many standard deviations as squares, beyond as L1
  // (Huber), so that noise averages out and a wrong fix pulls with bounded force.
  double prior_huber_sigmas = 1.0;
  TranslationSolver solver = TranslationSolver::kIrls;
  // IRLS: steps at most; stop when the positions change by less than irls_tolerance (relative);
  // residual floor of the weights 1 / max(|r|, irls_min_residual) (scales are >= 1, so positions
  // are in units of at least the shortest baseline and 1e-4 is far below any real residual).
  // The cap leaves room for a sequence's slow scale drift (irls_extrapolation below), within
  // which the benchmark sets converge.
  int max_irls_iterations = 50;
  double irls_tolerance = 1e-5;
  // IRLS also stops when a step that moved under 1% of the pair scales between held and free
  // lowered its objective (the sum of block residual norms, smoothed below the floor) by less than
  // this fraction of the objective's excess over its least value; the better iterate is kept.
  // Off by default: it saves steps on the long synthetic drives at no cost in accuracy there, but
  // the one real sequence converges slowly and loses accuracy by it at any tolerance that saves
  // steps (BENCHMARKS.md, "Scale"). 0: the steps stop on irls_tolerance or the cap alone.
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
  // mode on sequences is the scale drifting along them, which plain steps undo a little at a time:
  // plain steps reach the cap on the real sequence and the long drives before the positions
  // settle. Extrapolated steps settle within it, at the same accuracy; 2.5 needed the fewest steps
  // of the factors tried (BENCHMARKS.md, "Scale").
  double irls_extrapolation = 2.5;
  // Threads that assemble each IRLS step's equations (the mapper's --Mapper.num_threads; set by
  // the mapper, not an option). A window of a sequence is solved on one: the windows run side by
  // side.
  int num_threads = 1;
  // Each IRLS step first solves its camera system by conjugate gradients preconditioned with the
  // last Cholesky factor and started at the last solution, and refactorises only when that does
  // not reach a residual of pcg_tolerance times the right-hand side's within max_pcg_iterations
  // (forecast from the rate of the first three iterations: early steps reweight much and give up
  // at once). Late steps reweight little and converge within the cap, each iteration far cheaper
  // than a refactorisation of a long drive's system, so most factorisations are saved at the same
  // accuracy; a lower cap without the forecast saved as many but lost the time in abandoned
  // iterations (BENCHMARKS.md, "Scale"). 0: refactorise at every step.
  int max_pcg_iterations = 40;
  double pcg_tolerance = 1e-8;
  // ADMM penalty parameter, the starting value; with admm_adaptive_rho it is then balanced
  // against the residuals as the iterations go, so it sets only where the balancing starts.
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
  // Also stop when the L1 cost changes by less than this fraction over 50 iterations: past that,
  // ADMM's long tail moves the centres by far less than their noise, for many more iterations.
  double admm_cost_tolerance = 1e-5;

  void Check() const;
};

// Its options (--TranslationAveraging.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<TranslationAveragingOptions>& TranslationAveragingOptionTable();

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
    const std::vector<PosePriorInModel>& priors = {});

}  // namespace ramap
