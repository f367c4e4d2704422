#include "ramap/mapper/mapper.h"

#include <algorithm>
#include <iomanip>
#include <ostream>

#include "ramap/estimators/relative_poses.h"
#include "ramap/mapper/calibration_passes.h"
#include "ramap/mapper/component_rotations.h"
#include "ramap/mapper/component_translations.h"
#include "ramap/mapper/component_triangulation.h"
#include "ramap/mapper/components.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_state.h"
#include "ramap/mapper/refinement.h"
#include "ramap/util/blas_threads.h"
#include "ramap/util/error.h"
#include "ramap/util/memory.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

std::vector<std::string> ImageNames(const FeatureDatabase& database) {
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  return names;
}

// What the stages worked on (tracks, pair directions, the graph) released: only the model, the
// summary and the report outlive a component.
ComponentState Released(ComponentState state) {
  state.graph = RotationGraph();
  state.early_tracks = EarlyTracks();
  state.rotations.clear();
  state.edge_status.clear();
  state.translations.reset();
  state.poses.clear();
  return state;
}

// Stages 3-6 for one connected component of the view graph, in the method's order. A component
// whose translation averaging fails ends there, without a model (its report says why).
ComponentState ReconstructComponent(const PassInput& input, const RefinementPlan& refinement,
                                    RotationGraph graph) {
  ComponentState state;
  state.graph = std::move(graph);
  // The tracks, meanwhile, on a thread of their own (with more than one mapper thread).
  state.early_tracks = StartComponentTracks(input, state.graph);
  // 3. Rotation averaging: keyframe windows first for sequences, the whole graph for collections.
  state = AverageComponentRotations(input, std::move(state));
  // 4. Translation averaging: pair directions with the averaged rotations, then feature tracks;
  // with pose priors, the alignment to them and translation averaging again with them.
  state = AverageComponentTranslations(input, std::move(state));
  if (!state.translations) return Released(std::move(state));
  state = AlignComponentToPriors(input, std::move(state));
  // 5. Triangulation with the poses fixed; images its points leave out placed again from them.
  state = TriangulateAveragedPoses(input, std::move(state));
  state = ReregisterComponent(input, std::move(state));
  // 6. Bundle adjustment (the final one, or the subset's) and triangulation again.
  if (input.options.AdjustsAfterAveraging())
    state = RefineComponent(input, refinement, std::move(state));
  // Reported with the errors of the final model.
  state = ReportPriorErrors(input, std::move(state));
  state.summary.num_images = static_cast<int>(state.model.images.size());
  state.made = true;
  return Released(std::move(state));
}

// What one pass made, and what decides whether a second one follows.
struct PassOutcome {
  MapperResult result;
  ViewGraphCalibrationSummary calibration;
  bool calibration_pass = false;
  std::set<uint32_t> disproved_cameras;  // given focal lengths the test proved wrong
};

// The pass's models, largest first, and its summary, written from the states of the pass
// (`report`, `outcome`'s calibration) and of its components (in the order they were made).
void WritePassResult(const FeatureDatabase& database, const PosePriors& priors,
                     std::vector<ComponentState> components, StageReport report,
                     PassOutcome* outcome) {
  MapperResult& result = outcome->result;
  MapperSummary& summary = result.summary;
  std::vector<ComponentState*> made;
  for (ComponentState& component : components) {
    AppendReport(component.report, &report);
    if (component.made) made.push_back(&component);
  }
  std::stable_sort(made.begin(), made.end(), [](const ComponentState* a, const ComponentState* b) {
    return a->model.images.size() > b->model.images.size();
  });
  for (ComponentState* component : made) {
    if (component->prior_alignment.summary.aligned) result.geodetic_origin = priors.origin;
    outcome->disproved_cameras.insert(component->disproved_cameras.begin(),
                                      component->disproved_cameras.end());
    summary.components.push_back(std::move(component->summary));
    result.reconstructions.push_back(std::move(component->model));
  }
  summary.calibration_pass = outcome->calibration_pass;
  summary.num_keyframes = report.num_keyframes;
  summary.num_loop_edges = report.num_loop_edges;
  summary.dropped_edges = std::move(report.dropped_edges);
  summary.prior_outliers = std::move(report.prior_outliers);
  summary.timings = std::move(report.timings);
  ListUnregisteredImages(database, result.reconstructions, &report.image_reasons, &summary);
  summary.cameras = SummariseIntrinsics(database, outcome->calibration, result.reconstructions);
}

// Stage 1: the view graph's pairs and their relative poses, the accepted ones in `graph`. Throws
// InputError (naming `source`) when no pair gives a relative pose.
std::vector<ImagePair> EstimateViewGraph(const FeatureDatabase& database,
                                         const ImageBearings& bearings,
                                         const MapperOptions& options, const std::string& source,
                                         std::ostream* progress, MapperSummary* summary,
                                         StageReport* report, RotationGraph* graph) {
  Timer timer;
  std::vector<ImagePair> pairs =
      EstimateRelativePoses(database, bearings, options.relative_pose, options.num_threads);
  summary->num_verified_pairs = static_cast<int>(pairs.size());
  *graph = RotationGraphOfAcceptedPairs(database, pairs, report);
  summary->num_relative_poses = static_cast<int>(graph->edges.size());
  RecordStage(stage::kRelativePoses, timer.ElapsedSeconds(),
              std::to_string(graph->edges.size()) + " of " + std::to_string(pairs.size()) +
                  " verified pairs (" + CorrespondenceSamplerName(options.relative_pose.sampler) +
                  " sampler)",
              progress, report);
  if (graph->edges.empty()) {
    throw InputError(
        source, pairs.empty() ? WhyNoVerifiedPairs(database, options.relative_pose.min_num_inliers)
                              : "no image pair gave a relative pose (all " +
                                    std::to_string(pairs.size()) + " rejected)");
  }
  return pairs;
}

// Every stage once. `given_cameras` replaces the database's intrinsics (and view-graph calibration
// is skipped) when set: the second pass of RunMapper.
PassOutcome RunMapperPass(const FeatureDatabase& database, const MapperOptions& options,
                          const std::string& source, std::ostream* progress,
                          const PosePriors& priors,
                          const std::map<uint32_t, Camera>* given_cameras) {
  Timer total;
  PassOutcome outcome;
  MapperSummary& summary = outcome.result.summary;
  StageReport report;
  summary.num_images = static_cast<int>(database.images.size());
  if (database.images.empty()) throw InputError(source, "the database has no images");
  for (const auto& [id, image] : database.images)
    report.image_reasons[id] = "no verified pair with a usable geometry";

  // 0. The focal lengths the database does not know, from the view graph's F matrices.
  std::map<uint32_t, Camera> cameras = given_cameras ? *given_cameras : database.cameras;
  if (!given_cameras) {
    // Given focal lengths the user holds (bundle adjustment refines none) are not tested.
    ViewGraphCalibrationOptions calibration = options.view_graph_calibration;
    calibration.test_given_focal_lengths &= options.bundle_adjustment.refine_focal_length;
    outcome.calibration = CalibrateFocalLengths(
        database, calibration, &cameras, options.bundle_adjustment.share_identical_intrinsics);
  }
  LogViewGraphCalibration(outcome.calibration, progress, &report);
  const FirstPass first = FirstPassOptions(options, outcome.calibration);
  outcome.calibration_pass = first.calibration_pass;
  const MapperOptions& pass_options = first.options;
  Timer timer;
  const ImageBearings bearings = ComputeBearings(database, cameras, source);
  RecordStage(stage::kBearings, timer.ElapsedSeconds(),
              std::to_string(bearings.bearings.size()) + " images", progress, &report);

  // 1. Relative rotations of every verified pair.
  RotationGraph graph;
  const std::vector<ImagePair> pairs = EstimateViewGraph(database, bearings, pass_options, source,
                                                         progress, &summary, &report, &graph);

  // 2. The view graph, one reconstruction per connected component (stages 3-6).
  summary.sequential = IsSequentialInput(options.order, ImageNames(database));
  const std::vector<uint32_t> order = ImageIdsInCaptureOrder(database);
  const PassInput input{
      database, pass_options,           cameras, bearings, pairs, order, summary.sequential,
      priors,   first.calibration_pass, progress};
  const RefinementPlan refinement = PlanRefinement(pass_options, first.calibration_pass);
  std::vector<ComponentState> components;
  for (RotationGraph& component :
       ComponentsToReconstruct(graph, options.min_component_size, database, &report)) {
    components.push_back(ReconstructComponent(input, refinement, std::move(component)));
  }
  WritePassResult(database, priors, std::move(components), std::move(report), &outcome);
  summary.total_seconds = total.ElapsedSeconds();
  if (outcome.result.reconstructions.empty()) {
    throw NothingReconstructed(source, "no component of at least " +
                                           std::to_string(options.min_component_size) +
                                           " images could be reconstructed");
  }
  return outcome;
}

}  // namespace

MapperResult RunMapper(const FeatureDatabase& database, const MapperOptions& given_options,
                       const std::string& source, std::ostream* progress,
                       const PosePriors& priors) {
  MapperOptions options = given_options;
  options.Check();
  const ScopedBlasThreads blas_threads(options.num_threads);
  PassOutcome first = RunMapperPass(database, options, source, progress, priors, nullptr);
  first.result.summary.peak_rss_mib = PeakResidentMebibytes();
  if (!options.AdjustsAfterAveraging() || !(options.max_focal_change_in_bundle_adjustment > 0))
    return first.result;
  std::map<uint32_t, Camera> written;
  const double change = FocalChangeInBundleAdjustment(
      database, first.calibration, first.disproved_cameras, first.result.reconstructions, &written);
  if (change <= options.max_focal_change_in_bundle_adjustment && !first.calibration_pass)
    return first.result;
  std::map<uint32_t, Camera> refined = database.cameras;
  for (const auto& [camera_id, camera] : written) refined[camera_id] = camera;
  if (progress != nullptr) {
    *progress << "[ramap] bundle adjustment moved a focal length by " << std::fixed
              << std::setprecision(1) << 100 * change << "%"
              << (first.calibration_pass ? " (a calibration pass)" : "")
              << ": averaging again through the refined intrinsics\n";
  }
  PassOutcome second =
      RunMapperPass(database, SecondPassOptions(options), source, progress, priors, &refined);
  MergePassSummaries(first.result.summary, &second.result.summary);
  second.result.summary.peak_rss_mib = PeakResidentMebibytes();
  return second.result;
}

}  // namespace ramap
