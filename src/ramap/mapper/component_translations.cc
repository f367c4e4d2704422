#include "ramap/mapper/component_translations.h"

#include <algorithm>
#include <future>
#include <iterator>
#include <map>
#include <set>
#include <utility>

#include "ramap/averaging/direction_consistency.h"
#include "ramap/averaging/windowed_translation_averaging.h"
#include "ramap/graph/tracks.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_summary.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/util/error.h"
#include "ramap/util/even_subset.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

// The edges rotation averaging kept between two rotated images: every pair id, the pairs with a
// translation, and the pure rotations (both ways, for PlaceStandstillImages).
struct KeptEdges {
  std::set<uint64_t> pair_ids;
  std::vector<const ImagePair*> with_translation;
  std::multimap<uint32_t, uint32_t> pure_rotation_neighbours;
};

KeptEdges SplitKeptEdges(const PassInput& input, const RotationGraph& graph,
                         const std::vector<EdgeStatus>& edge_status,
                         const std::map<uint32_t, Eigen::Quaterniond>& world_rotations) {
  KeptEdges kept;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (edge_status[e] != EdgeStatus::kKept) continue;
    const ImagePair& pair = input.pairs[graph.edges[e].pair_index];
    if (!world_rotations.count(pair.image_id1) || !world_rotations.count(pair.image_id2)) continue;
    kept.pair_ids.insert(ImagePairToPairId(pair.image_id1, pair.image_id2));
    if (!(pair.estimate.flags & kRelativePosePureRotation)) {
      kept.with_translation.push_back(&pair);
      continue;
    }
    kept.pure_rotation_neighbours.emplace(pair.image_id1, pair.image_id2);
    kept.pure_rotation_neighbours.emplace(pair.image_id2, pair.image_id1);
  }
  return kept;
}

// The direction of each of the `kept` pairs from its inlier bearings and the averaged rotations,
// on the mapper's threads.
std::vector<PairDirection> KeptPairDirections(
    const PassInput& input, const std::vector<const ImagePair*>& kept,
    const std::map<uint32_t, Eigen::Quaterniond>& world_rotations) {
  std::vector<std::optional<Eigen::Vector3d>> found(kept.size());
  ParallelFor(kept.size(), input.options.num_threads, [&](size_t k) {
    const ImagePair& pair = *kept[k];
    const std::vector<FeatureMatch> inlier_matches =
        EvenSubset(InlierMatches(pair, input.database.two_view_geometries.at(
                                           ImagePairToPairId(pair.image_id1, pair.image_id2))),
                   input.options.pair_direction.max_num_matches);
    std::vector<Eigen::Vector3d> f1, f2;
    f1.reserve(inlier_matches.size());
    f2.reserve(inlier_matches.size());
    const std::vector<Eigen::Vector3d>& bearings1 = input.bearings.bearings.at(pair.image_id1);
    const std::vector<Eigen::Vector3d>& bearings2 = input.bearings.bearings.at(pair.image_id2);
    for (const FeatureMatch& match : inlier_matches) {
      f1.push_back(bearings1[match.point2D_idx1]);
      f2.push_back(bearings2[match.point2D_idx2]);
    }
    found[k] = EstimatePairDirection(world_rotations.at(pair.image_id1),
                                     world_rotations.at(pair.image_id2), f1, f2,
                                     input.options.pair_direction);
  });
  std::vector<PairDirection> directions;
  for (size_t k = 0; k < kept.size(); ++k) {
    if (found[k]) directions.push_back({kept[k]->image_id1, kept[k]->image_id2, *found[k]});
  }
  return directions;
}

// The directions their short cycles support (averaging/direction_consistency.h); each rejected one
// is listed with its reason among the summary's dropped edges, and its pair id added to
// `rejected_pair_ids`.
std::vector<PairDirection> ConsistentDirections(const PassInput& input,
                                                const std::vector<PairDirection>& directions,
                                                std::set<uint64_t>* rejected_pair_ids,
                                                ComponentState* state) {
  DirectionConsistencyResult checked =
      CheckDirectionCycles(directions, input.options.direction_consistency);
  for (const RejectedDirection& rejected : checked.rejected) {
    rejected_pair_ids->insert(ImagePairToPairId(rejected.image_id1, rejected.image_id2));
    state->report.dropped_edges.push_back(
        {PairName(input.database, rejected.image_id1, rejected.image_id2),
         "pair direction off its cycles by " + FormatDegrees(rejected.consistency_deg) +
             " (lower quartile of " + std::to_string(rejected.num_cycles) + " cycles) > " +
             FormatDegrees(rejected.threshold_deg) + " (direction check round " +
             std::to_string(rejected.round) + ")"});
  }
  state->summary.num_rejected_directions = static_cast<int>(checked.rejected.size());
  state->summary.direction_median_residual_deg = checked.median_consistency_deg;
  state->summary.direction_threshold_deg = checked.threshold_deg;
  return std::move(checked.kept);
}

// The pair rows translation averaging dropped as outliers, each once (a pair two windows share may
// be dropped by both), among the summary's dropped edges with the solution's miss.
void ListRejectedPairRows(const PassInput& input, const TranslationAveragingResult& positions,
                          ComponentState* state) {
  std::set<std::pair<uint32_t, uint32_t>> listed;
  for (const RejectedPairRow& row : positions.rejected_pair_rows) {
    if (!listed.insert({row.image_id1, row.image_id2}).second) continue;
    state->report.dropped_edges.push_back(
        {PairName(input.database, row.image_id1, row.image_id2),
         "translation averaging's solution misses the pair direction by " +
             FormatDegrees(row.miss_deg) + " > " + FormatDegrees(row.threshold_deg) +
             " (an outlier row, solved again without it)"});
  }
  state->summary.num_rejected_translation_rows = positions.num_rejected_rows;
}

// Tracks are built on a thread of their own with more than one mapper thread, otherwise when first
// asked for.
std::launch TracksLaunch(const PassInput& input) {
  return input.options.num_threads > 1 ? std::launch::async : std::launch::deferred;
}

// Whether the early tracks were built over exactly the `kept` edges.
bool EarlyTracksFit(const EarlyTracks& early, const KeptEdges& kept) {
  return early.built.valid() && early.pair_ids == kept.pair_ids;
}

// The tracks of the `kept` edges, on a thread of their own while the pair directions are
// estimated, which shortens the two together; the early tracks, which do not fit, are dropped
// first.
std::future<std::vector<Track>> TracksOfKeptEdges(const PassInput& input, const KeptEdges& kept,
                                                  EarlyTracks* early) {
  early->built = {};  // their memory freed (an async build is waited for)
  return std::async(TracksLaunch(input), [&database = input.database, &kept] {
    return BuildTracks(database.two_view_geometries, kept.pair_ids);
  });
}

// Images that only pure rotations link to the rest (the car waiting at a light, a panorama turned
// on one spot) have no direction to any other camera and are left out by translation averaging;
// a pure rotation means the two centres coincide (against the scene's depth), so each such image
// stands at the mean centre of its positioned pure-rotation neighbours, spreading along chains of
// them. Returns how many were placed.
int PlaceStandstillImages(const std::multimap<uint32_t, uint32_t>& rotation_neighbours,
                          TranslationAveragingResult* positions) {
  std::vector<uint32_t>& left_out = positions->unconstrained_images;
  const size_t num_left_out = left_out.size();
  for (bool placed = true; placed;) {
    placed = false;
    for (auto it = left_out.begin(); it != left_out.end();) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0;
      const auto [begin, end] = rotation_neighbours.equal_range(*it);
      for (auto neighbour = begin; neighbour != end; ++neighbour) {
        const auto found = positions->centers.find(neighbour->second);
        if (found != positions->centers.end()) sum += found->second, ++count;
      }
      if (count == 0) {
        ++it;
        continue;
      }
      positions->centers[*it] = sum / count;
      it = left_out.erase(it);
      placed = true;
    }
  }
  return static_cast<int>(num_left_out - left_out.size());
}

// The prior alignment's progress line.
std::string PriorAlignmentLine(const PriorAlignmentSummary& geo) {
  if (!geo.aligned) return "not aligned to its priors: " + geo.problem;
  return std::to_string(geo.num_inliers) + " of " + std::to_string(geo.num_priors) +
         " priors within " + FormatMetres(geo.threshold_m) + ", RMSE " + FormatMetres(geo.rmse_m) +
         ", " + std::to_string(geo.outliers.size()) + " outliers" +
         (geo.used_in_translation_averaging ? ", used in translation averaging" : "");
}

// The alignment to the priors, and translation averaging again with them (AlignComponentToPriors).
PriorAlignment RefitWithPriors(const PassInput& input,
                               const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                               ComponentTranslations* translations) {
  TranslationAveragingResult* positions = &translations->positions;
  const PriorAlignmentOptions& options = input.options.prior_alignment;
  PriorAlignment alignment = AlignCentersToPriors(positions->centers, input.priors, options);
  if (!alignment.summary.aligned || !options.use_in_translation_averaging) return alignment;
  try {
    TranslationAveragingResult constrained = AverageTranslations(
        rotations, translations->directions, translations->tracks, input.bearings.bearings,
        input.options.TranslationAveragingWithThreads(), PriorsInModelFrame(alignment));
    PriorAlignment refit = AlignCentersToPriors(constrained.centers, input.priors, options);
    if (!refit.summary.aligned) return alignment;
    refit.summary.used_in_translation_averaging = true;
    *positions = std::move(constrained);
    PlaceStandstillImages(translations->pure_rotation_neighbours, positions);
    return refit;
  } catch (const StageFailure&) {
    return alignment;  // the positions without priors stand
  }
}

// Translation averaging of the component: in windows for a long enough sequence
// (WindowedTranslationOptions), in one system otherwise or when the windows cannot be joined.
// `how` receives the progress line's note on it.
TranslationAveragingResult SolvePositions(const PassInput& input,
                                          const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                          const ComponentTranslations& inputs, std::string* how) {
  const WindowedTranslationOptions& windowed = input.options.translation_windows;
  if (input.sequential && windowed.min_num_images > 0 &&
      rotations.size() >= static_cast<size_t>(windowed.min_num_images)) {
    try {
      TranslationAveragingResult positions = AverageTranslationsInWindows(
          input.order, rotations, inputs.directions, inputs.tracks, input.bearings.bearings,
          input.options.TranslationAveragingWithThreads(), windowed, input.options.num_threads);
      *how = ", in " + std::to_string(positions.num_windows) + " windows";
      return positions;
    } catch (const StageFailure& error) {
      *how = ", in one system (" + std::string(error.what()) + ")";
    }
  }
  return AverageTranslations(rotations, inputs.directions, inputs.tracks, input.bearings.bearings,
                             input.options.TranslationAveragingWithThreads());
}

}  // namespace

EarlyTracks StartComponentTracks(const PassInput& input, const RotationGraph& graph) {
  EarlyTracks early;
  for (const RelativeRotationEdge& edge : graph.edges) {
    const ImagePair& pair = input.pairs[edge.pair_index];
    early.pair_ids.insert(ImagePairToPairId(pair.image_id1, pair.image_id2));
  }
  // The set is copied: `early` moves when returned.
  early.built =
      std::async(TracksLaunch(input), [&database = input.database, pair_ids = early.pair_ids] {
        return BuildTracks(database.two_view_geometries, pair_ids);
      });
  return early;
}

ComponentState AverageComponentTranslations(const PassInput& input, ComponentState state) {
  Timer timer;
  ComponentTranslations result;
  KeptEdges kept = SplitKeptEdges(input, state.graph, state.edge_status, state.rotations);
  const bool early_fits = EarlyTracksFit(state.early_tracks, kept);
  std::future<std::vector<Track>> tracks =
      early_fits ? std::move(state.early_tracks.built)
                 : TracksOfKeptEdges(input, kept, &state.early_tracks);
  std::set<uint64_t> rejected;
  result.directions = ConsistentDirections(
      input, KeptPairDirections(input, kept.with_translation, state.rotations), &rejected, &state);
  result.tracks = tracks.get();
  result.tracks_built_early = early_fits;
  if (!rejected.empty()) {
    // A rejected pair's matches are as wrong as its direction: where they join a track they would
    // give every prediction from that camera a wrong ray, and triangulation a wrong observation.
    std::set<uint64_t> pair_ids;
    std::set_difference(kept.pair_ids.begin(), kept.pair_ids.end(), rejected.begin(),
                        rejected.end(), std::inserter(pair_ids, pair_ids.end()));
    result.tracks = BuildTracks(input.database.two_view_geometries, pair_ids);
    result.tracks_built_early = false;
  }
  TranslationAveragingResult& positions = result.positions;
  std::string how;
  try {
    positions = SolvePositions(input, state.rotations, result, &how);
  } catch (const StageFailure& error) {
    for (const auto& [id, rotation] : state.rotations)
      state.report.image_reasons[id] = error.what();
    RecordStage(input, stage::kTranslationAveraging, timer.ElapsedSeconds(), error.what(), &state);
    return state;
  }
  ListRejectedPairRows(input, positions, &state);
  result.pure_rotation_neighbours = std::move(kept.pure_rotation_neighbours);
  const int num_standstill = PlaceStandstillImages(result.pure_rotation_neighbours, &positions);
  for (const uint32_t id : positions.unconstrained_images) {
    state.report.image_reasons[id] =
        "no translation constraint links it to the rest (too little parallax?)";
  }
  MapperComponentSummary& summary = state.summary;
  summary.num_translation_constraints = positions.num_constraints;
  summary.num_solver_iterations = positions.num_solver_iterations;
  summary.num_factorizations = positions.num_factorizations;
  summary.num_translation_windows = positions.num_windows;
  RecordStage(input, stage::kTranslationAveraging, timer.ElapsedSeconds(),
              std::to_string(positions.centers.size()) + " positions from " +
                  std::to_string(result.directions.size()) + " pair directions (" +
                  std::to_string(summary.num_rejected_directions) +
                  " rejected by their cycles) and " + std::to_string(positions.num_tracks_used) +
                  " tracks, " + std::to_string(positions.num_solver_iterations) +
                  " solver iterations (" + std::to_string(positions.num_factorizations) +
                  " factorisations)" + how +
                  (num_standstill > 0 ? ", " + std::to_string(num_standstill) +
                                            " placed by pure rotations (standing still)"
                                      : ""),
              &state);
  state.translations = std::move(result);
  return state;
}

ComponentState AlignComponentToPriors(const PassInput& input, ComponentState state) {
  if (input.priors.by_image.empty() || !input.options.prior_alignment.align) return state;
  Timer timer;
  state.prior_alignment = RefitWithPriors(input, state.rotations, &*state.translations);
  RecordStage(input, stage::kPriorAlignment, timer.ElapsedSeconds(),
              PriorAlignmentLine(state.prior_alignment.summary), &state);
  return state;
}

ComponentState ReportPriorErrors(const PassInput& input, ComponentState state) {
  PriorAlignment& alignment = state.prior_alignment;
  if (alignment.summary.aligned) {
    MeasurePriorErrors(state.model, input.priors, alignment.inliers, &alignment.summary);
    const PriorAlignmentSummary& geo = alignment.summary;
    for (const PriorOutlier& outlier : geo.outliers) {
      state.report.prior_outliers.push_back({input.database.images.at(outlier.image_id).name,
                                             "prior " + FormatMetres(outlier.error_m) +
                                                 " from the aligned camera centre (> " +
                                                 FormatMetres(geo.threshold_m) + "): not used"});
    }
  }
  state.summary.prior_alignment = alignment.summary;
  return state;
}

}  // namespace ramap
