#include "ramap/features/matching_plan.h"

#include <algorithm>
#include <set>
#include <tuple>

#include "ramap/scene/image_order.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

std::pair<uint32_t, uint32_t> Ordered(uint32_t a, uint32_t b) {
  return {std::min(a, b), std::max(a, b)};
}

// The mode kAuto stands for, and why.
std::pair<MatchingMode, std::string> ChooseMode(const FeatureMatchingOptions& options,
                                                const FeatureDatabase& database) {
  const int num_images = static_cast<int>(database.images.size());
  if (options.mode != MatchingMode::kAuto) return {options.mode, "asked for by --Matching.mode"};
  if (num_images <= options.auto_exhaustive_max_images) {
    return {MatchingMode::kExhaustive,
            std::to_string(num_images) +
                " images, at most --Matching.auto_exhaustive_max_images (" +
                std::to_string(options.auto_exhaustive_max_images) + ")"};
  }
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  if (LooksSequential(names)) {
    return {MatchingMode::kSequential,
            std::to_string(num_images) + " images whose names are frame numbers of one sequence"};
  }
  return {MatchingMode::kRetrieval,
          std::to_string(num_images) + " images whose names are not frame numbers of one sequence"};
}

}  // namespace

MatchingPlan PlanMatching(const FeatureMatchingOptions& options, const FeatureDatabase& database) {
  options.Check();
  MatchingPlan plan;
  std::tie(plan.mode, plan.reason) = ChooseMode(options, database);
  const std::vector<uint32_t> ordered = ImageIdsInCaptureOrder(database);
  std::set<std::pair<uint32_t, uint32_t>> planned;
  auto add = [&](std::vector<std::pair<uint32_t, uint32_t>>* list, uint32_t a, uint32_t b) {
    const auto pair = Ordered(a, b);
    if (a != b && planned.insert(pair).second) list->push_back(pair);
  };
  if (plan.mode == MatchingMode::kExhaustive) {
    for (size_t a = 0; a < ordered.size(); ++a) {
      for (size_t b = a + 1; b < ordered.size(); ++b)
        add(&plan.pairs_to_screen, ordered[a], ordered[b]);
    }
    return plan;
  }
  if (plan.mode == MatchingMode::kSequential) {
    for (size_t a = 0; a < ordered.size(); ++a) {
      const size_t last = std::min(ordered.size(), a + 1 + options.overlap);
      for (size_t b = a + 1; b < last; ++b) add(&plan.unscreened_pairs, ordered[a], ordered[b]);
    }
    if (options.loop_num_neighbors == 0) return plan;
  }
  Timer timer;
  const GlobalDescriptors global =
      ComputeGlobalDescriptors(database, ordered, options.retrieval, options.num_threads);
  const bool video = plan.mode == MatchingMode::kSequential;
  for (const auto& [a, b] : MostSimilarPairs(
           global, video ? options.loop_num_neighbors : options.retrieval_num_neighbors,
           video ? options.loop_min_frame_gap : 0)) {
    add(video ? &plan.pairs_to_screen : &plan.unscreened_pairs, a, b);
  }
  plan.retrieval_seconds = timer.ElapsedSeconds();
  return plan;
}

DatabaseMatchingSummary MatchDatabase(FeatureDatabase* database,
                                      const FeatureMatchingOptions& options,
                                      std::ostream* progress) {
  options.Check();
  Timer timer;
  const MatchingPlan plan = PlanMatching(options, *database);
  DatabaseMatchingSummary summary;
  summary.mode = plan.mode;
  summary.reason = plan.reason;
  summary.retrieval_seconds = plan.retrieval_seconds;
  summary.num_unscreened_pairs = static_cast<int>(plan.unscreened_pairs.size());
  summary.num_pairs_to_screen = static_cast<int>(plan.pairs_to_screen.size());
  std::vector<std::pair<uint32_t, uint32_t>> pairs = plan.unscreened_pairs;
  Timer screening;
  if (options.preemptive_num_features > 0) {
    const auto kept = ScreenPairsPreemptively(*database, plan.pairs_to_screen, options, progress);
    pairs.insert(pairs.end(), kept.begin(), kept.end());
  } else {
    pairs.insert(pairs.end(), plan.pairs_to_screen.begin(), plan.pairs_to_screen.end());
  }
  summary.screening_seconds = screening.ElapsedSeconds();
  summary.num_pairs_kept_by_screening =
      static_cast<int>(pairs.size()) - summary.num_unscreened_pairs;
  database->matches.clear();
  database->two_view_geometries.clear();
  const MatchingSummary matched = MatchImagePairs(database, pairs, options, progress);
  summary.num_pairs = matched.num_pairs;
  summary.num_verified_pairs = matched.num_verified_pairs;
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

}  // namespace ramap
