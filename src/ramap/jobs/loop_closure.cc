#include "ramap/jobs/loop_closure.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>

#include "ramap/scene/image_order.h"
#include "ramap/util/error.h"
#include "ramap/util/timer.h"

namespace ramap {

namespace {

// Every step-th element of `ids` (all of them with step 1).
std::vector<uint32_t> EverySampled(const std::vector<uint32_t>& ids, size_t step) {
  std::vector<uint32_t> sampled;
  for (size_t k = 0; k < ids.size(); k += step) sampled.push_back(ids[k]);
  return sampled;
}

// Unmatched pairs between every two groups (the models, then the unregistered images), at most
// max_pairs per two groups, the images of both sampled evenly.
std::vector<std::pair<uint32_t, uint32_t>> BridgePairs(const MapperResult& first,
                                                       const FeatureDatabase& database,
                                                       const std::set<uint64_t>& matched,
                                                       int max_pairs) {
  std::vector<std::vector<uint32_t>> groups;
  std::set<uint32_t> registered;
  for (const Reconstruction& reconstruction : first.reconstructions) {
    groups.emplace_back();
    for (const auto& [id, image] : reconstruction.images) {
      groups.back().push_back(id);
      registered.insert(id);
    }
  }
  std::vector<uint32_t> unregistered;
  for (const auto& [id, image] : database.images) {
    if (!registered.count(id)) unregistered.push_back(id);
  }
  if (!unregistered.empty()) groups.push_back(unregistered);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t a = 0; a < groups.size(); ++a) {
    for (size_t b = a + 1; b < groups.size(); ++b) {
      const double product = static_cast<double>(groups[a].size()) * groups[b].size();
      const size_t step =
          std::max<size_t>(1, static_cast<size_t>(std::ceil(std::sqrt(product / max_pairs))));
      for (const uint32_t i : EverySampled(groups[a], step)) {
        for (const uint32_t j : EverySampled(groups[b], step)) {
          const uint32_t id1 = std::min(i, j), id2 = std::max(i, j);
          if (!matched.count(ImagePairToPairId(id1, id2))) pairs.emplace_back(id1, id2);
        }
      }
    }
  }
  return pairs;
}

}  // namespace

void LoopClosureOptions::Check() const { CheckOptionValues(LoopClosureOptionTable(), *this); }

LoopClosureSummary MatchLoopCandidates(const MapperResult& first, const LoopClosureOptions& options,
                                       const FeatureMatchingOptions& matching,
                                       FeatureDatabase* database, std::ostream* progress) {
  options.Check();
  Timer timer;
  LoopClosureSummary summary;
  const std::vector<uint32_t> order = ImageIdsInCaptureOrder(*database);
  std::set<uint64_t> matched;
  for (const auto& [pair_id, matches] : database->matches) matched.insert(pair_id);
  for (const auto& [pair_id, geometry] : database->two_view_geometries) matched.insert(pair_id);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const Reconstruction& reconstruction : first.reconstructions) {
    for (const LoopCandidate& candidate :
         FindLoopCandidates(reconstruction, order, matched, options.candidates)) {
      pairs.emplace_back(candidate.image_id1, candidate.image_id2);
    }
  }
  summary.num_candidates = static_cast<int>(pairs.size());
  std::vector<std::pair<uint32_t, uint32_t>> bridges;
  const bool split =
      first.reconstructions.size() > 1 ||
      first.summary.num_registered_images < static_cast<int>(database->images.size());
  if (options.max_bridge_pairs > 0 && split) {
    bridges = BridgePairs(first, *database, matched, options.max_bridge_pairs);
    summary.num_bridge_pairs = static_cast<int>(bridges.size());
    bridges = ScreenPairsPreemptively(*database, bridges, matching, progress);
    summary.num_bridge_pairs_matched = static_cast<int>(bridges.size());
  }
  if (!pairs.empty()) {
    summary.num_verified = MatchImagePairs(database, pairs, matching, progress).num_verified_pairs;
    for (const auto& [id1, id2] : pairs) {
      const auto geometry = database->two_view_geometries.find(ImagePairToPairId(id1, id2));
      if (geometry == database->two_view_geometries.end()) continue;
      summary.loops.push_back(database->images.at(id1).name + " " + database->images.at(id2).name +
                              ": " + std::to_string(geometry->second.inlier_matches.size()) +
                              " inliers");
    }
  }
  if (!bridges.empty()) {
    summary.num_bridge_pairs_verified =
        MatchImagePairs(database, bridges, matching, progress).num_verified_pairs;
  }
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

namespace {

void PrintLoopClosure(const LoopClosureSummary& closure, std::ostream& out) {
  out << "[ramap] loop closure: " << closure.num_verified << " of " << closure.num_candidates
      << " candidate pairs verified";
  if (closure.num_bridge_pairs > 0) {
    out << "; between models " << closure.num_bridge_pairs_verified << " verified of "
        << closure.num_bridge_pairs_matched << " matched of " << closure.num_bridge_pairs
        << " screened";
  }
  out << ", " << std::fixed << std::setprecision(2) << closure.seconds << " s\n";
}

}  // namespace

LoopClosedMapperResult RunMapperWithLoopClosure(FeatureDatabase* database,
                                                const MapperOptions& options, bool close_loops,
                                                const LoopClosureOptions& closure_options,
                                                const FeatureMatchingOptions& matching,
                                                const std::string& source, std::ostream* progress,
                                                const PosePriors& priors) {
  LoopClosedMapperResult closed;
  closed.result = RunMapper(*database, options, source, progress, priors);
  if (!close_loops) return closed;
  closed.closure =
      MatchLoopCandidates(closed.result, closure_options, matching, database, progress);
  if (progress != nullptr) PrintLoopClosure(closed.closure, *progress);
  closed.database_changed =
      closed.closure.num_verified + closed.closure.num_bridge_pairs_verified > 0;
  if (closed.database_changed) {
    closed.result = RunMapper(*database, options, source, progress, priors);
  }
  return closed;
}

nlohmann::json LoopClosureToJson(bool enable, const LoopClosureOptions& options,
                                 const LoopClosureSummary& closure) {
  const LoopCandidateOptions& loops = options.candidates;
  return {{"enable", enable},
          {"max_distance_baselines", loops.max_distance_baselines},
          {"max_view_angle_deg", loops.max_view_angle_deg},
          {"min_frame_gap", loops.min_frame_gap},
          {"num_candidates", closure.num_candidates},
          {"num_verified", closure.num_verified},
          {"max_bridge_pairs", options.max_bridge_pairs},
          {"num_bridge_pairs", closure.num_bridge_pairs},
          {"num_bridge_pairs_matched", closure.num_bridge_pairs_matched},
          {"num_bridge_pairs_verified", closure.num_bridge_pairs_verified},
          {"loops", closure.loops}};
}

}  // namespace ramap
