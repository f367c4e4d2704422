#include "ramap/mapper/component_rotations.h"

#include <string>

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

}  // namespace

ComponentState AverageComponentRotations(const PassInput& input, ComponentState state) {
  const MapperOptions& options = input.options;
  Timer timer;
  RotationAveragingOptions rotation_averaging = options.rotation_averaging;
  rotation_averaging.use_edge_weights =
      UseRotationEdgeWeights(options.rotation_edge_weights, input.database);
  const RotationStageResult averaged = AverageGraphRotations(
      state.graph, input.order, input.sequential, options.view_graph, rotation_averaging);
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
          (rotations.certificate.certified ? "certified globally optimal" : "not certified"),
      &state);
  return state;
}

}  // namespace ramap
