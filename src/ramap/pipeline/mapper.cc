#include "ramap/pipeline/mapper.h"

#include <algorithm>
#include <iomanip>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ramap/graph/tracks.h"
#include "ramap/pipeline/bearings.h"
#include "ramap/pipeline/relative_poses.h"
#include "ramap/pipeline/rotation_stage.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/scene/image_order.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

std::vector<std::string> ImageNames(const FeatureDatabase& database) {
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  return names;
}

std::string PairName(const FeatureDatabase& database, uint32_t id1, uint32_t id2) {
  return database.images.at(id1).name + " " + database.images.at(id2).name;
}

std::string Degrees(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << value << " deg";
  return out.str();
}

// Everything the per-component stages share.
struct MapperContext {
  const FeatureDatabase& database;
  const MapperOptions& options;
  // The intrinsics the stages use: the database's, with view-graph estimates where it had none.
  const std::map<uint32_t, Camera>& cameras;
  const ImageBearings& bearings;
  const std::vector<ViewGraphEdge>& view_edges;
  const std::vector<uint32_t>& order;
  bool sequential;
  StageLog& log;
  MapperSummary& summary;
  std::map<uint32_t, std::string>& image_reasons;
  const PositionPriors& priors;
};

std::string Metres(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << value << " m";
  return out.str();
}

// Fits the averaged model to the priors; with the fit and use_in_translation_averaging, solves
// translation averaging again with the inlier priors as rows (in the model frame) and fits once
// more, so that the outliers and the residuals reported are those of the final positions.
PriorAlignment GeoregisterPositions(const MapperContext& context,
                                    const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                    const std::vector<PairDirection>& directions,
                                    const std::vector<TranslationTrack>& tracks,
                                    TranslationAveragingResult* positions) {
  const GeoregistrationOptions& options = context.options.georegistration;
  PriorAlignment alignment = AlignCentersToPriors(positions->centers, context.priors, options);
  if (!alignment.summary.georegistered || !options.use_in_translation_averaging) return alignment;
  try {
    TranslationAveragingResult constrained =
        AverageTranslations(rotations, directions, tracks, context.options.translation_averaging,
                            PriorsInModelFrame(alignment));
    PriorAlignment refit = AlignCentersToPriors(constrained.centers, context.priors, options);
    if (!refit.summary.georegistered) return alignment;
    refit.summary.used_in_translation_averaging = true;
    *positions = std::move(constrained);
    return refit;
  } catch (const std::runtime_error&) {
    return alignment;  // the positions without priors stand
  }
}

// Bundle adjustment on the best-connected points, then every track triangulated again with the
// refined poses (and, when BA refined them, through the refined intrinsics: they change every
// bearing of the component's images). `triangulate(poses, bearings, cameras, what)` rebuilds
// `reconstruction`.
template <typename Triangulate>
void RefineComponent(const MapperContext& context, bool georegistered,
                     const Triangulate& triangulate, PriorAlignment* georegistration,
                     MapperComponentSummary* component, Reconstruction* reconstruction) {
  const MapperOptions& options = context.options;
  Reconstruction adjusted = PointsForBundleAdjustment(*reconstruction, options.bundle_adjustment);
  const bool use_priors = georegistered && options.georegistration.use_in_bundle_adjustment;
  component->bundle_adjustment =
      BundleAdjust(context.bearings.bearings, context.bearings.focal_lengths_px, &adjusted,
                   options.bundle_adjustment,
                   use_priors ? georegistration->inliers : std::map<uint32_t, PositionPrior>());
  georegistration->summary.used_in_bundle_adjustment = use_priors;
  const BundleAdjustmentSummary& ba = component->bundle_adjustment;
  context.log.Record(stage::kBundleAdjustment, ba.seconds,
                     std::to_string(ba.num_points) + " points, RMSE " +
                         std::to_string(ba.initial_rmse_px) + " -> " +
                         std::to_string(ba.final_rmse_px) + " px, " +
                         std::to_string(ba.num_iterations) + " iterations");
  std::map<uint32_t, Rigid3d> refined;
  std::vector<uint32_t> image_ids;
  for (const auto& [id, image] : adjusted.images) {
    refined[id] = image.cam_from_world;
    image_ids.push_back(id);
  }
  const bool intrinsics_refined =
      std::any_of(adjusted.cameras.begin(), adjusted.cameras.end(), [&](const auto& entry) {
        return RefinesIntrinsics(options.bundle_adjustment, entry.second.model);
      });
  if (!intrinsics_refined) {
    triangulate(refined, context.bearings, context.cameras, "again with the refined poses: ");
    return;
  }
  std::map<uint32_t, Camera> refined_cameras = context.cameras;
  for (const auto& [camera_id, camera] : adjusted.cameras) refined_cameras[camera_id] = camera;
  const ImageBearings refined_bearings =
      ComputeBearings(context.database, refined_cameras, "bundle adjustment", image_ids);
  triangulate(refined, refined_bearings, refined_cameras,
              "again with the refined poses and intrinsics: ");
}

// Stage 3 for one component: rotation averaging (keyframe windows first for sequences, the whole
// graph for collections). The estimated rotations go to `world_rotations`; images left without
// one and pruned edges are recorded with their reasons.
RotationStageResult AverageComponentRotations(
    const MapperContext& context, const RotationGraph& graph, MapperComponentSummary* component,
    std::map<uint32_t, Eigen::Quaterniond>* world_rotations) {
  const MapperOptions& options = context.options;
  Timer timer;
  RotationStageResult stage = AverageViewGraphRotations(
      graph, context.order, context.sequential, options.pose_graph, options.rotation_averaging);
  const RotationAveragingResult& rotations = stage.rotations;
  context.summary.num_keyframes += stage.num_keyframes;
  context.summary.num_loop_edges += stage.num_loop_edges;
  for (size_t k = 0; k < rotations.node_ids.size(); ++k) {
    if (rotations.estimated[k]) {
      (*world_rotations)[rotations.node_ids[k]] = rotations.rotations[k];
    } else {
      context.image_reasons[rotations.node_ids[k]] =
          "rotation not estimated (cut off by pruned edges)";
    }
  }
  for (const PrunedEdge& pruned : rotations.pruned_edges) {
    const RelativeRotationEdge& edge = graph.edges[pruned.edge_index];
    context.summary.dropped_edges.push_back(
        {PairName(context.database, edge.i, edge.j),
         pruned.reason == EdgeStatus::kPrunedResidual
             ? "rotation residual " + Degrees(pruned.residual_deg) + " > alpha_max " +
                   Degrees(pruned.threshold_deg) + " (pruning round " +
                   std::to_string(pruned.round) + ")"
             : "outside the largest connected component after pruning"});
  }
  component->num_rotation_edges = static_cast<int>(graph.edges.size());
  component->num_pruned_edges = static_cast<int>(rotations.pruned_edges.size());
  component->rotation_certified = rotations.certificate.certified;
  component->certificate_bound_deg = rotations.certificate.bound_deg;
  component->max_rotation_residual_deg = rotations.certificate.max_robust_residual_deg;
  context.log.Record(
      stage::kRotationAveraging, timer.ElapsedSeconds(),
      std::to_string(world_rotations->size()) + " rotations, " +
          std::to_string(rotations.pruned_edges.size()) + " edges pruned, " +
          (rotations.certificate.certified ? "certified globally optimal" : "not certified"));
  return stage;
}

// The direction of every edge rotation averaging kept between two rotated images (pure rotations
// aside), from its inlier bearings and the averaged rotations; `kept_pairs` gets every kept pair.
std::vector<PairDirection> KeptPairDirections(
    const MapperContext& context, const RotationGraph& graph,
    const std::vector<size_t>& graph_to_view_edge, const std::vector<EdgeStatus>& edge_status,
    const std::map<uint32_t, Eigen::Quaterniond>& world_rotations, std::set<uint64_t>* kept_pairs) {
  std::vector<PairDirection> directions;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (edge_status[e] != EdgeStatus::kKept) continue;
    const ViewGraphEdge& view_edge = context.view_edges[graph_to_view_edge[e]];
    if (!world_rotations.count(view_edge.image_id1) || !world_rotations.count(view_edge.image_id2))
      continue;
    kept_pairs->insert(ImagePairToPairId(view_edge.image_id1, view_edge.image_id2));
    if (view_edge.estimate.flags & kRelativePosePureRotation) continue;
    std::vector<Eigen::Vector3d> f1, f2;
    for (const int k : view_edge.estimate.inliers) {
      f1.push_back(view_edge.correspondences.bearings1[k]);
      f2.push_back(view_edge.correspondences.bearings2[k]);
    }
    const std::optional<Eigen::Vector3d> direction = EstimatePairDirection(
        world_rotations.at(view_edge.image_id1), world_rotations.at(view_edge.image_id2), f1, f2,
        context.options.pair_direction);
    if (direction) directions.push_back({view_edge.image_id1, view_edge.image_id2, *direction});
  }
  return directions;
}

// The tracks' observations by rotated images, as bearings; tracks left with fewer than two are
// dropped.
std::vector<TranslationTrack> TranslationTracks(
    const std::vector<Track>& tracks, const ImageBearings& bearings,
    const std::map<uint32_t, Eigen::Quaterniond>& world_rotations) {
  std::vector<TranslationTrack> translation_tracks;
  translation_tracks.reserve(tracks.size());
  for (const Track& track : tracks) {
    TranslationTrack observations;
    for (const TrackElement& element : track) {
      if (!world_rotations.count(element.image_id)) continue;
      observations.push_back(
          {element.image_id, bearings.bearings.at(element.image_id)[element.point2D_idx]});
    }
    if (observations.size() >= 2) translation_tracks.push_back(std::move(observations));
  }
  return translation_tracks;
}

// Stage 4 for one component; none when translation averaging fails (its images get the reason).
std::optional<TranslationAveragingResult> AverageComponentTranslations(
    const MapperContext& context, const std::map<uint32_t, Eigen::Quaterniond>& world_rotations,
    const std::vector<PairDirection>& directions,
    const std::vector<TranslationTrack>& translation_tracks, MapperComponentSummary* component) {
  Timer timer;
  TranslationAveragingResult positions;
  try {
    positions = AverageTranslations(world_rotations, directions, translation_tracks,
                                    context.options.translation_averaging);
  } catch (const std::runtime_error& error) {
    for (const auto& [id, rotation] : world_rotations) context.image_reasons[id] = error.what();
    context.log.Record(stage::kTranslationAveraging, timer.ElapsedSeconds(), error.what());
    return std::nullopt;
  }
  for (const uint32_t id : positions.unconstrained_images) {
    context.image_reasons[id] =
        "no translation constraint links it to the rest (too little parallax?)";
  }
  component->num_translation_constraints = positions.num_constraints;
  component->num_solver_iterations = positions.num_solver_iterations;
  context.log.Record(stage::kTranslationAveraging, timer.ElapsedSeconds(),
                     std::to_string(positions.centers.size()) + " positions from " +
                         std::to_string(directions.size()) + " pair directions and " +
                         std::to_string(positions.num_tracks_used) + " tracks, " +
                         std::to_string(positions.num_solver_iterations) + " solver iterations");
  return positions;
}

// The georegistration's progress line.
std::string GeoregistrationLine(const GeoregistrationSummary& geo) {
  if (!geo.georegistered) return "not georegistered: " + geo.problem;
  return std::to_string(geo.num_inliers) + " of " + std::to_string(geo.num_priors) +
         " priors within " + Metres(geo.threshold_m) + ", RMSE " + Metres(geo.rmse_m) + ", " +
         std::to_string(geo.outliers.size()) + " outliers" +
         (geo.used_in_translation_averaging ? ", used in translation averaging" : "");
}

// After the final model: the priors' errors, and the outliers reported with them.
void ReportPriorErrors(const MapperContext& context, const Reconstruction& reconstruction,
                       PriorAlignment* georegistration) {
  MeasurePriorErrors(reconstruction, context.priors, georegistration->inliers,
                     &georegistration->summary);
  const GeoregistrationSummary& geo = georegistration->summary;
  for (const PriorOutlier& outlier : geo.outliers) {
    context.summary.prior_outliers.push_back({context.database.images.at(outlier.image_id).name,
                                              "prior " + Metres(outlier.error_m) +
                                                  " from the aligned camera centre (> " +
                                                  Metres(geo.threshold_m) + "): not used"});
  }
}

// Stages 2-6 for one connected component of the view graph. Returns false (with reasons recorded)
// when the component cannot be reconstructed.
bool ReconstructComponent(const MapperContext& context, const RotationGraph& graph,
                          const std::vector<size_t>& graph_to_view_edge,
                          Reconstruction* reconstruction) {
  const FeatureDatabase& database = context.database;
  const MapperOptions& options = context.options;
  MapperComponentSummary component;

  std::map<uint32_t, Eigen::Quaterniond> world_rotations;
  const RotationStageResult stage =
      AverageComponentRotations(context, graph, &component, &world_rotations);

  // Translation averaging: pair directions with the averaged rotations, then feature tracks.
  std::set<uint64_t> kept_pairs;
  const std::vector<PairDirection> directions =
      KeptPairDirections(context, graph, graph_to_view_edge, stage.rotations.edge_status,
                         world_rotations, &kept_pairs);
  TrackBuildSummary track_summary;
  const std::vector<Track> tracks =
      BuildTracks(database.two_view_geometries, kept_pairs, {}, &track_summary);
  const std::vector<TranslationTrack> translation_tracks =
      TranslationTracks(tracks, context.bearings, world_rotations);
  std::optional<TranslationAveragingResult> averaged = AverageComponentTranslations(
      context, world_rotations, directions, translation_tracks, &component);
  if (!averaged) return false;
  TranslationAveragingResult& positions = *averaged;

  // Georegistration with the position priors.
  PriorAlignment georegistration;
  if (!context.priors.by_image.empty() && options.georegistration.align) {
    Timer georegistration_timer;
    georegistration =
        GeoregisterPositions(context, world_rotations, directions, translation_tracks, &positions);
    context.log.Record(stage::kGeoregistration, georegistration_timer.ElapsedSeconds(),
                       GeoregistrationLine(georegistration.summary));
  }
  const bool georegistered = georegistration.summary.georegistered;

  // Structure: triangulate every track with the poses fixed.
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [id, center] : positions.centers) {
    const Eigen::Quaterniond& R = world_rotations.at(id);
    poses[id] = Rigid3d(R, -(R * center));
    if (georegistered) poses[id] = TransformPose(georegistration.prior_from_model, poses[id]);
  }
  auto triangulate = [&](const std::map<uint32_t, Rigid3d>& fixed_poses,
                         const ImageBearings& bearings, const std::map<uint32_t, Camera>& cameras,
                         const std::string& what) {
    Timer structure_timer;
    StructureSummary structure;
    *reconstruction = BuildReconstruction(database, fixed_poses, tracks, bearings.bearings,
                                          bearings.focal_lengths_px, options.structure, &structure);
    for (auto& [camera_id, camera] : reconstruction->cameras) camera = cameras.at(camera_id);
    component.num_points = structure.num_points;
    component.num_observations = structure.num_observations;
    component.mean_reprojection_error_px = structure.mean_reprojection_error_px;
    context.log.Record(stage::kTriangulation, structure_timer.ElapsedSeconds(),
                       what + std::to_string(structure.num_points) + " points of " +
                           std::to_string(tracks.size()) + " tracks, mean reprojection error " +
                           std::to_string(structure.mean_reprojection_error_px) + " px");
  };
  triangulate(poses, context.bearings, context.cameras, "");

  if (options.refine) {
    RefineComponent(context, georegistered, triangulate, &georegistration, &component,
                    reconstruction);
  }
  // Reported with the errors of the final model, as in the component's summary.
  if (georegistered) ReportPriorErrors(context, *reconstruction, &georegistration);
  component.georegistration = georegistration.summary;
  component.num_images = static_cast<int>(reconstruction->images.size());
  context.summary.components.push_back(component);
  return true;
}

// Each camera's intrinsics as given, as the view graph estimated them, and as written (from the
// largest model that holds the camera).
std::vector<CameraIntrinsicsSummary> SummariseIntrinsics(
    const FeatureDatabase& database, const ViewGraphCalibrationSummary& calibration,
    const std::vector<Reconstruction>& reconstructions) {
  std::vector<CameraIntrinsicsSummary> cameras;
  for (const auto& [camera_id, camera] : database.cameras) {
    CameraIntrinsicsSummary entry;
    entry.camera_id = camera_id;
    entry.model = CameraModelName(camera.model);
    entry.prior_focal_length_known = camera.has_prior_focal_length;
    entry.prior_params = camera.params;
    for (const CameraCalibration& estimate : calibration.cameras) {
      if (estimate.camera_id == camera_id) entry.view_graph = estimate;
    }
    for (const Reconstruction& reconstruction : reconstructions) {
      const auto written = reconstruction.cameras.find(camera_id);
      if (written == reconstruction.cameras.end()) continue;
      entry.final_params = written->second.params;
      break;
    }
    cameras.push_back(entry);
  }
  return cameras;
}

// Why the database has no pair the mapper can use, in the user's terms.
std::string WhyNoVerifiedPairs(const FeatureDatabase& database, int min_num_inliers) {
  if (database.two_view_geometries.empty()) {
    return "no image pair has verified matches (two_view_geometries is empty); run a matcher "
           "first";
  }
  int panoramic = 0, unusable = 0, few_inliers = 0;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (geometry.config == TwoViewConfig::kPanoramic) {
      ++panoramic;
    } else if (!IsUsableTwoViewConfig(geometry.config)) {
      ++unusable;
    } else if (static_cast<int>(geometry.inlier_matches.size()) < min_num_inliers) {
      ++few_inliers;
    }
  }
  const size_t total = database.two_view_geometries.size();
  std::string problem = "none of the " + std::to_string(total) + " verified pairs can be used: ";
  if (panoramic > 0) {
    problem += std::to_string(panoramic) +
               " PANORAMIC (pure rotation, as in a panorama: averaging needs the cameras to move "
               "between views), ";
  }
  if (unusable > 0) {
    problem += std::to_string(unusable) + " degenerate, watermark or of unknown geometry, ";
  }
  if (few_inliers > 0) {
    problem += std::to_string(few_inliers) + " with fewer than --RelativePose.min_num_inliers " +
               std::to_string(min_num_inliers) + " inliers, ";
  }
  return problem.substr(0, problem.size() - 2);
}

}  // namespace

void MapperOptions::Check() const {
  view_graph_calibration.Check();
  relative_pose.Check();
  if (!pose_graph.Check()) {
    throw InputError("--PoseGraph.keyframe_interval",
                     "must be >= 1, got " + std::to_string(pose_graph.keyframe_interval));
  }
  const std::string rotation_problem = rotation_averaging.Problem();
  if (!rotation_problem.empty()) throw InputError("--RotationAveraging", rotation_problem);
  pair_direction.Check();
  translation_averaging.Check();
  structure.Check();
  bundle_adjustment.Check();
  if (min_component_size < 2) {
    throw InputError("--Mapper.min_component_size",
                     "must be >= 2, got " + std::to_string(min_component_size));
  }
  if (num_threads < 1) {
    throw InputError("--Mapper.num_threads", "must be >= 1, got " + std::to_string(num_threads));
  }
  if (!(max_focal_change_in_bundle_adjustment >= 0)) {
    throw InputError("--Mapper.max_focal_change_in_bundle_adjustment", "must be >= 0");
  }
  CheckOption(calibration_num_points >= 0, "--Mapper.calibration_num_points", ">= 0",
              calibration_num_points);
}

namespace {

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

// One line for the view-graph calibration: each unknown camera's guess and estimate.
void LogViewGraphCalibration(const ViewGraphCalibrationSummary& calibration, StageLog* log) {
  if (calibration.cameras.empty()) return;
  int num_estimated = 0;
  std::ostringstream focal_lengths;
  for (const CameraCalibration& camera : calibration.cameras) {
    num_estimated += camera.estimated;
    if (focal_lengths.tellp() > 0) focal_lengths << ", ";
    focal_lengths << std::fixed << std::setprecision(1) << camera.prior_focal_px << " -> "
                  << (camera.estimated ? camera.estimated_focal_px : camera.prior_focal_px)
                  << " px";
  }
  log->Record(stage::kViewGraphCalibration, calibration.seconds,
              std::to_string(num_estimated) + " of " + std::to_string(calibration.cameras.size()) +
                  " uncalibrated cameras estimated (" + focal_lengths.str() + ")");
}

// The options of one pass: a calibration pass's BA (summary->calibration_pass) adjusts fewer
// points when the view graph left some camera's focal length unknown, since a second pass follows.
MapperOptions OptionsForThisPass(const MapperOptions& options,
                                 const ViewGraphCalibrationSummary& calibration,
                                 MapperSummary* summary) {
  const bool unknown_focal =
      std::any_of(calibration.cameras.begin(), calibration.cameras.end(),
                  [](const CameraCalibration& camera) { return !camera.estimated; });
  if (!options.refine || !unknown_focal || options.calibration_num_points == 0 ||
      !(options.max_focal_change_in_bundle_adjustment > 0) ||
      !options.bundle_adjustment.refine_focal_length) {
    return options;
  }
  MapperOptions pass = options;
  BundleAdjustmentOptions& ba = pass.bundle_adjustment;
  ba.max_num_points = ba.max_num_points == 0
                          ? options.calibration_num_points
                          : std::min(ba.max_num_points, options.calibration_num_points);
  ba.min_observations_per_image = std::min(ba.min_observations_per_image, 50);
  summary->calibration_pass = true;
  return pass;
}

// Stage 1's graph: the pairs whose relative pose was accepted, as rotation-graph edges
// (`graph_to_view_edge` maps each to its view edge); the rejected pairs and the images they leave
// without an edge go to `summary` and `image_reasons`.
RotationGraph AcceptedPoseGraph(const FeatureDatabase& database,
                                const std::vector<ViewGraphEdge>& view_edges,
                                std::vector<size_t>* graph_to_view_edge, MapperSummary* summary,
                                std::map<uint32_t, std::string>* image_reasons) {
  RotationGraph graph;
  std::set<uint32_t> nodes;
  for (size_t k = 0; k < view_edges.size(); ++k) {
    const ViewGraphEdge& edge = view_edges[k];
    if (!edge.estimate.success) {
      summary->dropped_edges.push_back({PairName(database, edge.image_id1, edge.image_id2),
                                        "relative pose rejected: " + edge.estimate.reason});
      for (const uint32_t id : {edge.image_id1, edge.image_id2}) {
        if (!nodes.count(id))
          (*image_reasons)[id] = "every relative pose rejected (" + edge.estimate.reason + ")";
      }
      continue;
    }
    graph.edges.push_back({edge.image_id1, edge.image_id2, edge.estimate.rotation,
                           RelativeRotationWeight(edge.estimate.num_inliers)});
    graph_to_view_edge->push_back(k);
    nodes.insert({edge.image_id1, edge.image_id2});
  }
  graph.node_ids.assign(nodes.begin(), nodes.end());
  return graph;
}

// The component of `graph` whose nodes carry `label`, reconstructed; none when it is smaller than
// min_component_size (its images get the reason) or cannot be reconstructed.
std::optional<Reconstruction> ReconstructLabelledComponent(
    const MapperContext& context, const RotationGraph& graph,
    const std::vector<size_t>& graph_to_view_edge, const std::vector<int>& labels, int label) {
  const int size = static_cast<int>(std::count(labels.begin(), labels.end(), label));
  const int min_size = context.options.min_component_size;
  if (size < min_size) {
    for (size_t k = 0; k < graph.node_ids.size(); ++k) {
      if (labels[k] != label) continue;
      context.image_reasons[graph.node_ids[k]] = "in a component of " + std::to_string(size) +
                                                 " images (< Mapper.min_component_size " +
                                                 std::to_string(min_size) + ")";
    }
    return std::nullopt;
  }
  const std::unordered_map<uint32_t, int> index = NodeIndex(graph);
  std::vector<bool> keep(graph.edges.size());
  for (size_t e = 0; e < graph.edges.size(); ++e)
    keep[e] = labels[index.at(graph.edges[e].i)] == label;
  std::vector<size_t> edge_map;
  const RotationGraph component_graph = Subgraph(graph, keep, &edge_map);
  std::vector<size_t> component_to_view_edge;
  for (const size_t e : edge_map) component_to_view_edge.push_back(graph_to_view_edge[e]);
  Reconstruction reconstruction;
  if (!ReconstructComponent(context, component_graph, component_to_view_edge, &reconstruction)) {
    return std::nullopt;
  }
  return reconstruction;
}

// Counts the registered images and lists every other one with its reason.
void ListUnregisteredImages(const FeatureDatabase& database,
                            const std::vector<Reconstruction>& reconstructions,
                            std::map<uint32_t, std::string>* image_reasons,
                            MapperSummary* summary) {
  for (const Reconstruction& reconstruction : reconstructions) {
    summary->num_registered_images += static_cast<int>(reconstruction.images.size());
    for (const auto& [id, image] : reconstruction.images) image_reasons->erase(id);
  }
  for (const auto& [id, reason] : *image_reasons)
    summary->dropped_images.push_back({database.images.at(id).name, reason});
}

// Every stage once. `given_cameras` replaces the database's intrinsics (and view-graph calibration
// is skipped) when set: the second pass of RunMapper.
MapperResult RunMapperPass(const FeatureDatabase& database, const MapperOptions& options,
                           const std::string& source, std::ostream* progress,
                           const PositionPriors& priors,
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

  // Stage 0: the focal lengths the database does not know, from the view graph's F matrices.
  std::map<uint32_t, Camera> cameras = given_cameras ? *given_cameras : database.cameras;
  const ViewGraphCalibrationSummary calibration =
      given_cameras ? ViewGraphCalibrationSummary()
                    : CalibrateFocalLengths(database, options.view_graph_calibration, &cameras);
  LogViewGraphCalibration(calibration, &log);
  const MapperOptions pass_options = OptionsForThisPass(options, calibration, &summary);

  Timer timer;
  const ImageBearings bearings = ComputeBearings(database, cameras, source);
  log.Record(stage::kBearings, timer.ElapsedSeconds(),
             std::to_string(bearings.bearings.size()) + " images");

  // Stage 1: relative rotations of every verified pair.
  timer.Restart();
  const std::vector<ViewGraphEdge> view_edges =
      EstimateRelativePoses(database, bearings, options.relative_pose, options.num_threads);
  summary.num_verified_pairs = static_cast<int>(view_edges.size());
  std::vector<size_t> graph_to_view_edge;
  const RotationGraph graph =
      AcceptedPoseGraph(database, view_edges, &graph_to_view_edge, &summary, &image_reasons);
  summary.num_relative_poses = static_cast<int>(graph.edges.size());
  log.Record(stage::kRelativePoses, timer.ElapsedSeconds(),
             std::to_string(graph.edges.size()) + " of " + std::to_string(view_edges.size()) +
                 " verified pairs (" + CorrespondenceSamplerName(options.relative_pose.sampler) +
                 " sampler)");
  if (graph.edges.empty()) {
    throw InputError(source,
                     view_edges.empty()
                         ? WhyNoVerifiedPairs(database, options.relative_pose.min_num_inliers)
                         : "no image pair gave a relative pose (all " +
                               std::to_string(view_edges.size()) + " rejected)");
  }

  // Stage 2: the pose graph, one reconstruction per connected component.
  summary.sequential = IsSequentialInput(options.order, ImageNames(database));
  const std::vector<uint32_t> order = ImageIdsInCaptureOrder(database);
  const std::vector<int> labels = ConnectedComponents(graph);
  const int num_components =
      labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  MapperContext context{database,           pass_options, cameras, bearings,      view_edges, order,
                        summary.sequential, log,          summary, image_reasons, priors};
  for (int label = 0; label < num_components; ++label) {
    std::optional<Reconstruction> reconstruction =
        ReconstructLabelledComponent(context, graph, graph_to_view_edge, labels, label);
    if (reconstruction) result.reconstructions.push_back(std::move(*reconstruction));
  }
  SortLargestFirst(&result);
  for (const MapperComponentSummary& component : summary.components) {
    if (component.georegistration.georegistered) result.geodetic_origin = priors.origin;
  }
  ListUnregisteredImages(database, result.reconstructions, &image_reasons, &summary);
  summary.cameras = SummariseIntrinsics(database, calibration, result.reconstructions);
  summary.total_seconds = total.ElapsedSeconds();
  if (result.reconstructions.empty()) {
    throw InputError(source, "no component of at least " +
                                 std::to_string(options.min_component_size) +
                                 " images could be reconstructed");
  }
  return result;
}

// The largest relative change of a focal length between the intrinsics averaging used and those
// bundle adjustment wrote, over the cameras of the largest model; and those cameras.
double FocalChangeInBundleAdjustment(const MapperResult& result,
                                     std::map<uint32_t, Camera>* refined) {
  double change = 0.0;
  for (const CameraIntrinsicsSummary& camera : result.summary.cameras) {
    if (camera.final_params.empty() || camera.prior_params.empty()) continue;
    // What averaging used: the view graph's estimate, else the database's value.
    const double used =
        camera.view_graph.estimated ? camera.view_graph.estimated_focal_px : camera.prior_params[0];
    change = std::max(change, std::abs(camera.final_params[0] / used - 1.0));
  }
  for (const Reconstruction& reconstruction : result.reconstructions) {
    for (const auto& [camera_id, camera] : reconstruction.cameras)
      refined->emplace(camera_id, camera);
  }
  return change;
}

}  // namespace

MapperResult RunMapper(const FeatureDatabase& database, const MapperOptions& options,
                       const std::string& source, std::ostream* progress,
                       const PositionPriors& priors) {
  options.Check();
  MapperResult first = RunMapperPass(database, options, source, progress, priors, nullptr);
  if (!options.refine || !(options.max_focal_change_in_bundle_adjustment > 0)) return first;
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
  // The intrinsics start where BA left them: the ordinary tolerance suffices (measured: templeRing
  // 62 -> 20 iterations, the same AUC).
  MapperOptions second_options = options;
  BundleAdjustmentOptions& ba = second_options.bundle_adjustment;
  ba.intrinsics_function_tolerance =
      std::max(ba.intrinsics_function_tolerance, ba.function_tolerance);
  MapperResult second = RunMapperPass(database, second_options, source, progress, priors, &refined);
  // One summary for both passes: the first pass's view-graph estimates, both passes' time.
  for (CameraIntrinsicsSummary& camera : second.summary.cameras) {
    for (const CameraIntrinsicsSummary& earlier : first.summary.cameras) {
      if (earlier.camera_id != camera.camera_id) continue;
      camera.view_graph = earlier.view_graph;
      camera.prior_params = earlier.prior_params;
    }
  }
  for (const MapperStageTiming& timing : first.summary.timings) {
    auto it = std::find_if(second.summary.timings.begin(), second.summary.timings.end(),
                           [&](const MapperStageTiming& t) { return t.stage == timing.stage; });
    if (it == second.summary.timings.end()) {
      second.summary.timings.push_back(timing);
    } else {
      it->seconds += timing.seconds;
    }
  }
  second.summary.total_seconds += first.summary.total_seconds;
  second.summary.num_averaging_passes = 2;
  second.summary.calibration_pass = first.summary.calibration_pass;
  return second;
}

}  // namespace ramap
