#include "ramap/pipeline/mapper.h"

#include <algorithm>
#include <iomanip>
#include <ostream>

#include "ramap/pipeline/calibration_passes.h"
#include "ramap/pipeline/components.h"
#include "ramap/pipeline/mapper_context.h"
#include "ramap/pipeline/mapper_option_table.h"
#include "ramap/pipeline/refine.h"
#include "ramap/pipeline/relative_poses.h"
#include "ramap/pipeline/reregistration.h"
#include "ramap/pipeline/rotations.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/pipeline/translations.h"
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

// The camera poses of the averaged rotations and centres, in the priors' frame when aligned to
// them.
std::map<uint32_t, Rigid3d> AveragedPoses(const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                          const TranslationAveragingResult& positions,
                                          const PriorAlignment& prior_alignment) {
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [id, center] : positions.centers) {
    const Eigen::Quaterniond& R = rotations.at(id);
    poses[id] = Rigid3d(R, -(R * center));
    if (prior_alignment.summary.aligned)
      poses[id] = TransformPose(prior_alignment.prior_from_model, poses[id]);
  }
  return poses;
}

// Stages 3-6 for one connected component of the view graph, in the method's order; none (with
// the reasons recorded) when the component cannot be reconstructed.
std::optional<Reconstruction> ReconstructComponent(const MapperContext& context,
                                                   const ViewGraph& graph) {
  const MapperOptions& options = context.options;
  MapperComponentSummary component;

  // The tracks, meanwhile, on a thread of their own (with more than one mapper thread).
  EarlyTracks early_tracks = StartComponentTracks(context, graph);
  // 3. Rotation averaging: keyframe windows first for sequences, the whole graph for collections.
  std::map<uint32_t, Eigen::Quaterniond> rotations;
  const RotationStageResult averaged =
      AverageComponentRotations(context, graph, &component, &rotations);

  // 4. Translation averaging: pair directions with the averaged rotations, then feature tracks.
  std::optional<ComponentTranslations> translations = AverageComponentTranslations(
      context, graph, averaged.rotations.edge_status, rotations, &early_tracks, &component);
  if (!translations) return std::nullopt;
  // With pose priors: prior alignment, and translation averaging again with them.
  PriorAlignment prior_alignment;
  if (!context.priors.by_image.empty() && options.prior_alignment.align)
    prior_alignment = AlignComponentToPriors(context, rotations, &*translations);
  const bool aligned = prior_alignment.summary.aligned;

  // 5. Triangulation: every track triangulated with the poses fixed (under the looser bound of a
  // BA's start when BA follows); images its points leave out placed again from them.
  std::map<uint32_t, Rigid3d> poses =
      AveragedPoses(rotations, translations->positions, prior_alignment);
  Reconstruction reconstruction =
      TriangulateComponent(context, poses, translations->tracks, context.bearings, context.cameras,
                           "", &component, options.TriangulationOfAveragedPoses());
  ReregisterComponent(context, translations->tracks, &poses, &component, &reconstruction);

  // 6. Bundle adjustment (the final one, or the subset's) and triangulation again.
  if (options.AdjustsAfterAveraging()) {
    RefineComponent(context, translations->tracks, &prior_alignment, &component, &reconstruction);
  }
  // Reported with the errors of the final model, as in the component's summary.
  if (aligned) ReportPriorErrors(context, reconstruction, &prior_alignment);
  component.prior_alignment = prior_alignment.summary;
  component.num_images = static_cast<int>(reconstruction.images.size());
  context.summary.components.push_back(component);
  return reconstruction;
}

// The models largest first, the component summaries in the same order.
void SortLargestFirst(MapperResult* result) {
  std::vector<size_t> by_size(result->reconstructions.size());
  for (size_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
  std::stable_sort(by_size.begin(), by_size.end(), [&](size_t a, size_t b) {
    return result->reconstructions[a].images.size() > result->reconstructions[b].images.size();
  });
  std::vector<Reconstruction> reconstructions;
  std::vector<MapperComponentSummary> components;
  for (const size_t k : by_size) {
    reconstructions.push_back(std::move(result->reconstructions[k]));
    components.push_back(result->summary.components[k]);
  }
  result->reconstructions = std::move(reconstructions);
  result->summary.components = std::move(components);
}

// Stage 1: the view graph's pairs and their relative poses, the accepted ones in `graph`. Throws
// InputError (naming `source`) when no pair gives a relative pose.
std::vector<ImagePair> EstimateViewGraph(const FeatureDatabase& database,
                                         const ImageBearings& bearings,
                                         const MapperOptions& options, const std::string& source,
                                         StageLog* log, MapperSummary* summary,
                                         std::map<uint32_t, std::string>* image_reasons,
                                         ViewGraph* graph) {
  Timer timer;
  std::vector<ImagePair> pairs =
      EstimateRelativePoses(database, bearings, options.relative_pose, options.num_threads);
  summary->num_verified_pairs = static_cast<int>(pairs.size());
  *graph = ViewGraphOfAcceptedPairs(database, pairs, summary, image_reasons);
  summary->num_relative_poses = static_cast<int>(graph->edges.size());
  log->Record(stage::kRelativePoses, timer.ElapsedSeconds(),
              std::to_string(graph->edges.size()) + " of " + std::to_string(pairs.size()) +
                  " verified pairs (" + CorrespondenceSamplerName(options.relative_pose.sampler) +
                  " sampler)");
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
MapperResult RunMapperPass(const FeatureDatabase& database, const MapperOptions& options,
                           const std::string& source, std::ostream* progress,
                           const PosePriors& priors,
                           const std::map<uint32_t, Camera>* given_cameras) {
  Timer total;
  MapperResult result;
  MapperSummary& summary = result.summary;
  StageLog log(&summary, progress);
  summary.num_images = static_cast<int>(database.images.size());
  if (database.images.empty()) throw InputError(source, "the database has no images");
  std::map<uint32_t, std::string> image_reasons;
  for (const auto& [id, image] : database.images)
    image_reasons[id] = "no verified pair with a usable geometry";

  // 0. The focal lengths the database does not know, from the view graph's F matrices.
  std::map<uint32_t, Camera> cameras = given_cameras ? *given_cameras : database.cameras;
  const ViewGraphCalibrationSummary calibration =
      given_cameras ? ViewGraphCalibrationSummary()
                    : CalibrateFocalLengths(database, options.view_graph_calibration, &cameras,
                                            options.bundle_adjustment.share_identical_intrinsics);
  LogViewGraphCalibration(calibration, &log);
  const MapperOptions pass_options = FirstPassOptions(options, calibration, &summary);
  Timer timer;
  const ImageBearings bearings = ComputeBearings(database, cameras, source);
  log.Record(stage::kBearings, timer.ElapsedSeconds(),
             std::to_string(bearings.bearings.size()) + " images");

  // 1. Relative rotations of every verified pair.
  ViewGraph graph;
  const std::vector<ImagePair> pairs = EstimateViewGraph(database, bearings, pass_options, source,
                                                         &log, &summary, &image_reasons, &graph);

  // 2. The view graph, one reconstruction per connected component (stages 3-6).
  summary.sequential = IsSequentialInput(options.order, ImageNames(database));
  const std::vector<uint32_t> order = ImageIdsInCaptureOrder(database);
  MapperContext context{database,           pass_options, cameras, bearings,      pairs, order,
                        summary.sequential, log,          summary, image_reasons, priors};
  for (const ViewGraph& component :
       ComponentsToReconstruct(graph, options.min_component_size, &image_reasons)) {
    std::optional<Reconstruction> reconstruction = ReconstructComponent(context, component);
    if (reconstruction) result.reconstructions.push_back(std::move(*reconstruction));
  }
  SortLargestFirst(&result);
  for (const MapperComponentSummary& component : summary.components) {
    if (component.prior_alignment.aligned) result.geodetic_origin = priors.origin;
  }
  ListUnregisteredImages(database, result.reconstructions, &image_reasons, &summary);
  summary.cameras = SummariseIntrinsics(database, calibration, result.reconstructions);
  summary.total_seconds = total.ElapsedSeconds();
  if (result.reconstructions.empty()) {
    throw NothingReconstructed(source, "no component of at least " +
                                           std::to_string(options.min_component_size) +
                                           " images could be reconstructed");
  }
  return result;
}

}  // namespace

MapperResult RunMapper(const FeatureDatabase& database, const MapperOptions& given_options,
                       const std::string& source, std::ostream* progress,
                       const PosePriors& priors) {
  MapperOptions options = given_options;
  ResolveMapperOptions(&options);
  const ScopedBlasThreads blas_threads(options.num_threads);
  MapperResult first = RunMapperPass(database, options, source, progress, priors, nullptr);
  first.summary.peak_rss_mib = PeakResidentMebibytes();
  if (!options.AdjustsAfterAveraging() || !(options.max_focal_change_in_bundle_adjustment > 0))
    return first;
  std::map<uint32_t, Camera> refined = database.cameras;
  std::map<uint32_t, Camera> written;
  const double change = FocalChangeInBundleAdjustment(first, &written);
  if (change <= options.max_focal_change_in_bundle_adjustment && !first.summary.calibration_pass)
    return first;
  for (const auto& [camera_id, camera] : written) refined[camera_id] = camera;
  if (progress != nullptr) {
    *progress << "[ramap] bundle adjustment moved a focal length by " << std::fixed
              << std::setprecision(1) << 100 * change << "%"
              << (first.summary.calibration_pass ? " (a calibration pass)" : "")
              << ": averaging again through the refined intrinsics\n";
  }
  MapperResult second =
      RunMapperPass(database, SecondPassOptions(options), source, progress, priors, &refined);
  MergePassSummaries(first.summary, &second.summary);
  second.summary.peak_rss_mib = PeakResidentMebibytes();
  return second;
}

}  // namespace ramap
