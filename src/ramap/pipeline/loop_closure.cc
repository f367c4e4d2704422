#include "ramap/pipeline/loop_closure.h"

#include <set>

#include "ramap/pipeline/image_order.h"
#include "ramap/util/timer.h"

namespace ramap {

LoopClosureSummary MatchLoopCandidates(const MapperResult& first,
                                       const LoopCandidateOptions& options,
                                       const FeatureMatchingOptions& matching,
                                       FeatureDatabase* database, std::ostream* progress) {
  Timer timer;
  LoopClosureSummary summary;
  std::vector<uint32_t> ids;
  std::vector<std::string> names;
  for (const auto& [id, image] : database->images) {
    ids.push_back(id);
    names.push_back(image.name);
  }
  std::vector<uint32_t> order;
  for (const size_t k : CaptureOrder(names)) order.push_back(ids[k]);
  std::set<uint64_t> matched;
  for (const auto& [pair_id, matches] : database->matches) matched.insert(pair_id);
  for (const auto& [pair_id, geometry] : database->two_view_geometries) matched.insert(pair_id);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const Reconstruction& reconstruction : first.reconstructions) {
    for (const LoopCandidate& candidate :
         FindLoopCandidates(reconstruction, order, matched, options)) {
      pairs.emplace_back(candidate.image_id1, candidate.image_id2);
    }
  }
  summary.num_candidates = static_cast<int>(pairs.size());
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
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
