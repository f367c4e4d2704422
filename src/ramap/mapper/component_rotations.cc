#include "ramap/mapper/component_rotations.h"

#include <iomanip>
#include <sstream>
#include <string>
#include <utility>

#include "ramap/estimators/rotation_folds.h"
#include "ramap/estimators/rotations.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

// What rotation averaging reports of a component: its pruned edges and unestimated images in the
// report, its figures in the summary.
void ReportRotations(const PassInput& input, const RotationAveragingResult& rotations,
                     ComponentState* state) {
  for (size_t k = 0; k < rotations.node_ids.size(); ++k) {
    if (!rotations.estimated[k]) {
      state->report.image_reasons[rotations.node_ids[k]] =
          "rotation not estimated (cut off by pruned edges)";
    }
  }
  for (const PrunedEdge& pruned : rotations.pruned_edges) {
    const RelativeRotationEdge& edge = state->graph.edges[pruned.edge_index];
    state->report.dropped_edges.push_back(
        {PairName(input.database, edge.i, edge.j),
         pruned.reason == EdgeStatus::kPrunedResidual
             ? "rotation residual " + FormatDegrees(pruned.residual_deg) + " > threshold " +
                   FormatDegrees(pruned.threshold_deg) + " (pruning round " +
                   std::to_string(pruned.round) + ")"
             : "outside the largest connected component after pruning"});
  }
  MapperComponentSummary& summary = state->summary;
  summary.num_rotation_edges = static_cast<int>(state->graph.edges.size());
  summary.num_pruned_edges = static_cast<int>(rotations.pruned_edges.size());
  summary.rotation_certified = rotations.certificate.certified;
  summary.certificate_bound_deg = rotations.certificate.bound_deg;
  summary.certificate_cycle_lower_bound_deg = rotations.certificate.cycle_residual_lower_bound_deg;
  summary.max_rotation_residual_deg = rotations.certificate.max_robust_residual_deg;
  summary.num_rotation_factorizations = rotations.factorizations;
  summary.rotation_seconds = rotations.timings;
}

// Where `averaged` is unweighted and the fold check is on: averaging again with inlier-count
// weights, and that solution in its place where it unfolds the first (rotation_folds.h). Returns
// what the stage line adds ("" when nothing changed).
std::string UnfoldRotations(const PassInput& input, const RotationGraph& graph,
                            RotationAveragingOptions options, RotationStageResult* averaged) {
  if (!input.options.rotation_fold_check || options.use_edge_weights) return "";
  options.use_edge_weights = true;
  RotationStageResult weighted = AverageGraphRotations(graph, input.order, input.sequential,
                                                       input.options.view_graph, options);
  const RotationSolutionComparison comparison =
      CompareRotationSolutions(graph, averaged->rotations, weighted.rotations);
  if (!SecondSolutionUnfolds(comparison, input.options.rotation_fold_min_difference_deg)) return "";
  *averaged = std::move(weighted);
  std::ostringstream note;
  note << std::fixed << std::setprecision(0) << "; the inlier-weighted solution kept: the "
       << "unweighted one folded the scene (up to " << comparison.largest_difference_deg
       << " deg apart; it left out pairs of " << comparison.left_out_weight_first
       << " inliers, the weighted one " << comparison.left_out_weight_second << ")";
  return note.str();
}

}  // namespace

ComponentState AverageComponentRotations(const PassInput& input, ComponentState state) {
  const MapperOptions& options = input.options;
  Timer timer;
  RotationAveragingOptions rotation_averaging = options.rotation_averaging;
  rotation_averaging.use_edge_weights =
      UseRotationEdgeWeights(options.rotation_edge_weights, input.database);
  RotationStageResult averaged = AverageGraphRotations(state.graph, input.order, input.sequential,
                                                       options.view_graph, rotation_averaging);
  const std::string unfolded = UnfoldRotations(input, state.graph, rotation_averaging, &averaged);
  const RotationAveragingResult& rotations = averaged.rotations;
  state.report.num_keyframes += averaged.num_keyframes;
  state.report.num_loop_edges += averaged.num_loop_edges;
  for (size_t k = 0; k < rotations.node_ids.size(); ++k) {
    if (rotations.estimated[k]) state.rotations[rotations.node_ids[k]] = rotations.rotations[k];
  }
  state.edge_status = rotations.edge_status;
  ReportRotations(input, rotations, &state);
  RecordStage(
      input, stage::kRotationAveraging, timer.ElapsedSeconds(),
      std::to_string(state.rotations.size()) + " rotations, " +
          std::to_string(rotations.pruned_edges.size()) + " edges pruned, " +
          (rotations.certificate.certified ? "certified globally optimal" : "not certified") +
          unfolded,
      &state);
  return state;
}

}  // namespace ramap
