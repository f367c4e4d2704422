// Robust rotation averaging with edge pruning and an optimality certificate, following
// "Pushing the Envelope of Rotation Averaging for Visual SLAM" (Li, Yuan, Latecki, Ling):
//   1. initialisation by chaining relative rotations along a maximum spanning tree (edge weights);
//   2. L1RA: a bounded number of iteratively reweighted L1 steps on the Lie-algebra linearisation
//      w_j - w_i = log(R_j^T R_ij R_i) (Chatterjee & Govindu, ICCV 2013 / TPAMI 2018);
//   3. IRLS with a robust loss (Geman-McClure by default) on the same linearisation;
//   4. pruning: edges whose residual angle exceeds a threshold are removed and IRLS re-runs, at
//      most max_pruning_rounds times; the threshold is a multiple of the kept edges' median
//      residual in the first round, held for the later ones, within [adaptive_min_deg,
//      alpha_max_deg] (the default), the paper's fixed angle alpha_max_deg (45 deg) or, in every
//      round, the strong-duality bound of Eriksson, Olsson, Kahl, Chin ("Rotation averaging and
//      strong duality", CVPR 2018);
//   5. certificate: on the kept graph, the chordal cost sum ||R_j - R_ij R_i||_F^2 is brought to a
//      stationary point from the robust solution, and that stationary point is certified globally
//      optimal (for the chordal problem on the kept edges) when every kept residual is at most the
//      bound alpha = 2 asin( sqrt(1/4 + lambda_2 / (2 d_max)) - 1/2 ) (graph/fiedler.h). The
//      result's rotations stay the robust solution either way. A triangle whose cycle angle
//      exceeds 3 alpha proves no solution can pass, and then the chordal refinement is skipped
//      (graph/cycle_consistency.h).
//
// Conventions in scene/rotation_graph.h: R_i is cam_from_world, an edge holds R_ij = R_j R_i^T.
// Updates are right perturbations R_k <- R_k exp([w_k]_x). With that linearisation every edge row
// of the 3E x 3N system is (-I, +I), so the normal matrix is (weighted Laplacian) (x) I_3: it is
// solved as one N x N Laplacian (gauge: one node held fixed) with three right-hand sides by
// CHOLMOD, whose symbolic analysis is done once per edge set and reused across iterations.
// The residual angle of an edge is the angle of R_j^T R_ij R_i, in degrees in all results.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "ramap/averaging/preconditioned_cg.h"
#include "ramap/graph/keyframes.h"
#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/util/option_table.h"

namespace ramap {

enum class RobustLoss {
  kGemanMcClure,  // rho(r) = r^2 / (r^2 + sigma^2), Chatterjee & Govindu's default
  kL1Half,        // rho(r) = |r|^(1/2)
};

enum class PruningThresholdMode {
  kFixedAngle,          // alpha_max_deg
  kStrongDualityBound,  // the Eriksson et al. bound of the current kept graph
  kAdaptive,            // adaptive_multiplier times the kept edges' median residual, clamped
};

struct RotationAveragingOptions {
  // L1RA relinearisations; the paper bounds L1RA and stops it early because IRLS refines anyway.
  int max_l1_iterations = 10;
  // Reweighted least-squares steps solving each linearised L1 problem (IRLS for L1).
  int l1_inner_iterations = 5;
  // L1RA stops when the RMS node update falls below this (degrees).
  double l1_step_tolerance_deg = 1e-2;
  // Floor on |r| in the L1 weights 1/|r| (degrees), so exact edges do not get infinite weight.
  double l1_min_residual_deg = 1e-4;
  // IRLS iterations per run (one run before pruning and one after each pruning round).
  int max_irls_iterations = 100;
  // IRLS stops when the RMS node update falls below this (degrees).
  double irls_step_tolerance_deg = 1e-6;
  // Each IRLS step (not L1's) first solves its tangent-space system by conjugate gradients,
  // preconditioned by the last factorisation and started from the last step, for at most this
  // many iterations (averaging/preconditioned_cg.h) and at most as many as cost a factorisation's
  // flops, and refactorises when they do not reach a residual of pcg_tolerance times the
  // right-hand side's. Graphs whose factor is cheap (fewer than 10 iterations' worth: most view
  // graphs without long loops) always refactorise. 0: refactorise at every step.
  int max_pcg_iterations = 40;
  double pcg_tolerance = 1e-8;
  RobustLoss loss = RobustLoss::kGemanMcClure;
  // Scale of the robust loss (degrees); Chatterjee & Govindu (TPAMI 2018) use 5 deg.
  double sigma_deg = 5.0;
  PruningThresholdMode pruning_mode = PruningThresholdMode::kAdaptive;
  // Residual angle above which an edge is pruned in kFixedAngle mode (paper: 45 deg); the
  // ceiling of the kAdaptive threshold.
  double alpha_max_deg = 45.0;
  // kAdaptive: edges are pruned above adaptive_multiplier times the median residual of the kept
  // edges after the first IRLS run (what noise gives in this graph; the later rounds keep that
  // threshold), but never below adaptive_min_deg and never above alpha_max_deg: a pair aliased by
  // repeated facades a few degrees off is an inlier to a fixed 45 deg and to the robust loss
  // alike, and bends a long sequence.
  double adaptive_multiplier = 6.0;
  double adaptive_min_deg = 1.0;
  // Pruning rounds, each followed by an IRLS run (paper: 3). 0 disables pruning.
  int max_pruning_rounds = 3;
  // In kFixedAngle and kAdaptive modes, a node with at least 3 kept edges of which a strict
  // majority exceed the threshold is taken as mis-estimated rather than surrounded by outliers:
  // its edges are not pruned in that round and it is re-initialised from the neighbour prediction
  // that most other predictions agree with (within the threshold). Without this, an L1 start that
  // left a node far off strands it on an outlier edge once its inlier edges are pruned (seen with
  // 30% outlier edges).
  bool reinitialize_suspect_nodes = true;
  // Scale IRLS weights by the edges' own weights (inlier counts). Off here as in Chatterjee &
  // Govindu; the mapper turns it on when every focal length is known (MapperOptions::
  // rotation_edge_weights).
  bool use_edge_weights = false;
  // Where edges are weighted, a weight saturates at this many times the median inlier count:
  // an edge of n inliers weighs n / (1 + n / n0), n0 = edge_weight_saturation x the median. A
  // relative rotation's error falls with its inliers only down to a floor (the bias of its pair's
  // geometry, shared by neighbouring pairs of a sequence), so its information is about
  // 1 / (sigma^2 / n + floor^2), not n; taking the floor as the noise of the median edge gives
  // n0 = the median. With n itself, a drive's short pairs (the most inliers) outweighed its
  // long ones and their shared bias drifted the rotations: on the second generator's KITTI 06
  // drives the rotation error median was 1.4-1.6 deg, 0.5-0.7 deg with this (0: n itself).
  double edge_weight_saturation = 1.0;
  // Compute the strong-duality certificate (a Fiedler value and a chordal refinement).
  bool compute_certificate = true;
  // Iterations and RMS-update tolerance (degrees) of the chordal refinement of the certificate.
  int max_certificate_iterations = 200;
  double certificate_step_tolerance_deg = 1e-8;
  // Before the chordal refinement, look for a triangle of kept edges whose cycle angle / 3 exceeds
  // the bound (graph/cycle_consistency.h): then no stationary point can be certified and the
  // refinement is skipped. It pays on graphs whose aliased edges are down-weighted but kept, as on
  // the long synthetic drives: the certificate gives the same (negative) answer in a fraction of
  // the time.
  bool certificate_cycle_check = true;

  // Throws InputError("--RotationAveraging.<option>", "must be ..., got V") for the first option
  // out of range (named RotationAveragingOptions::<field> when no command line sets it).
  void Check() const;
};

// Its options (--RotationAveraging.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<RotationAveragingOptions>& RotationAveragingOptionTable();

enum class EdgeStatus {
  kKept,
  kPrunedResidual,      // residual angle above the round's pruning threshold after an IRLS run
  kPrunedDisconnected,  // an end node is outside the largest connected component
};

struct PrunedEdge {
  size_t edge_index = 0;  // into graph.edges
  int round = 0;          // pruning round (1-based); 0 for edges dropped before averaging
  double residual_deg = 0.0;
  double threshold_deg = 0.0;
  EdgeStatus reason = EdgeStatus::kPrunedResidual;
};

struct RotationAveragingTimings {  // seconds
  double windows = 0.0;            // local window averaging and stitching (windowed entry only)
  double init = 0.0;               // spanning tree initialisation
  double l1 = 0.0;                 // L1RA
  double irls = 0.0;               // the first IRLS run
  double pruning = 0.0;            // pruning rounds, including their IRLS re-runs
  double certificate = 0.0;        // Fiedler value, triangle check and chordal refinement
  double total = 0.0;
};

struct RotationCertificate {
  bool computed = false;
  bool certified = false;         // every kept residual of the chordal stationary point <= bound
  double bound_deg = 0.0;         // alpha_max of Eriksson et al. for the kept graph
  double fiedler_value = 0.0;     // lambda_2 of the unweighted Laplacian of the kept graph
  int max_degree = 0;             // d_max of the kept graph
  double max_residual_deg = 0.0;  // of the chordal stationary point, kept edges
  double max_robust_residual_deg = 0.0;  // of the robust solution, kept edges
  int iterations = 0;                    // chordal refinement iterations
  // max over the triangles checked of cycle angle / 3: a lower bound on the largest kept residual
  // of any rotations. Above bound_deg, the refinement is skipped (refinement_skipped, iterations 0)
  // and max_residual_deg and rotations are those of the robust solution.
  double cycle_residual_lower_bound_deg = 0.0;
  bool refinement_skipped = false;
  std::vector<Eigen::Quaterniond> rotations;  // the chordal stationary point, per node position
};

struct RotationAveragingResult {
  std::vector<uint32_t> node_ids;             // as graph.node_ids
  std::vector<Eigen::Quaterniond> rotations;  // cam_from_world per node position
  std::vector<bool> estimated;                // false: outside the largest component
  std::vector<double> edge_residuals_deg;     // per graph edge; NaN when an end is not estimated
  std::vector<EdgeStatus> edge_status;        // per graph edge
  std::vector<PrunedEdge> pruned_edges;       // in pruning order
  int l1_iterations = 0;
  int irls_iterations = 0;  // over all IRLS runs
  // CHOLMOD factorisations of the whole graph's L1 and IRLS runs (not the windows' own solves,
  // nor the certificate's).
  int factorizations = 0;
  int pruning_rounds = 0;  // rounds that removed an edge or re-initialised a node
  std::vector<uint32_t> reinitialized_nodes;  // suspect nodes re-initialised during pruning
  RotationCertificate certificate;
  RotationAveragingTimings timings;
};

// The full pipeline from a maximum-spanning-tree initialisation. Throws InputError when options
// fail Check(), std::invalid_argument when the graph is malformed (see NodeIndex).
RotationAveragingResult AverageRotations(const RotationGraph& graph,
                                         const RotationAveragingOptions& options);

// The same from given rotations (per node position); nodes with initial_known[k] == false are
// initialised along the maximum spanning tree from the known ones.
RotationAveragingResult AverageRotationsFrom(const RotationGraph& graph,
                                             const std::vector<Eigen::Quaterniond>& initial,
                                             const std::vector<bool>& initial_known,
                                             const RotationAveragingOptions& options);

// Local windows first, then global (Li et al.): every keyframe window's sub-graph (edges with both
// ends in the window) is averaged on its own, window solutions are chained through their shared
// keyframes into a global initialisation (a window sharing no frame with earlier ones is attached
// through its heaviest edge to them), and the whole graph is then averaged from it.
RotationAveragingResult AverageRotationsInWindows(const RotationGraph& graph,
                                                  const Keyframes& keyframes,
                                                  const RotationAveragingOptions& options);

// Plain (non-robust) chordal averaging for comparison: the linear relaxation
// min sum ||X_j - R_ij X_i||_F^2 over 3x3 matrices with one node fixed (a 3N x 3N sparse system,
// CHOLMOD), each X_i projected onto SO(3) by SVD, then, with `refine`, iterated to a stationary
// point of the chordal cost. Only the largest connected component is estimated.
struct ChordalAveragingResult {
  std::vector<Eigen::Quaterniond> rotations;  // per node position
  std::vector<bool> estimated;
  int refine_iterations = 0;
  double seconds = 0.0;
};
ChordalAveragingResult AverageRotationsChordal(const RotationGraph& graph, bool refine = true,
                                               int max_refine_iterations = 200,
                                               double refine_step_tolerance_deg = 1e-8);

// sum over edges (with keep[e], all when empty; skipping edges with an end not estimated, when
// `estimated` is given) of ||R_j - R_ij R_i||_F^2 = 8 sin^2(angle / 2); unweighted.
double ChordalCost(const RotationGraph& graph, const std::vector<Eigen::Quaterniond>& rotations,
                   const std::vector<bool>& keep = {}, const std::vector<bool>& estimated = {});

// Residual angle (degrees) of one edge: the angle of R_j^T R_ij R_i.
double EdgeResidualDeg(const RelativeRotationEdge& edge, const Eigen::Quaterniond& R_i,
                       const Eigen::Quaterniond& R_j);

}  // namespace ramap
