// Which image pairs a database's matching tries, and the matching of them: the plan grows linearly
// with the images except where exhaustive matching is cheap (a few dozen images).
//   - sequential (a video): each frame with the next `overlap`, plus loop candidates found by
//     image retrieval;
//   - retrieval (an unordered collection): each image with its most similar images;
//   - exhaustive: every pair.
// Every pair of exhaustive matching and a video's loop candidates are screened preemptively
// before they are matched in full; a video's next frames and retrieval's neighbours are not
// (retrieval is the screen: screening its neighbours again with 100 features dropped most of
// them on a synthetic collection, pairs the mapper needs).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "ramap/features/feature_matching.h"

namespace ramap {

struct MatchingPlan {
  MatchingMode mode = MatchingMode::kExhaustive;             // auto resolved
  std::string reason;                                        // why this mode, in words
  // Matched in full: a video's next frames, or retrieval's neighbours.
  std::vector<std::pair<uint32_t, uint32_t>> unscreened_pairs;
  // Screened before full matching: every pair, or a video's loop candidates.
  std::vector<std::pair<uint32_t, uint32_t>> pairs_to_screen;
  double retrieval_seconds = 0.0;
};

// The plan for `database`'s images under `options` (kAuto: exhaustive up to
// auto_exhaustive_max_images images, else sequential when the names are frame numbers of one
// sequence, else retrieval). Pairs have the smaller image id first; none is listed twice.
MatchingPlan PlanMatching(const FeatureMatchingOptions& options, const FeatureDatabase& database);

struct DatabaseMatchingSummary {
  MatchingMode mode = MatchingMode::kExhaustive;
  std::string reason;
  int num_unscreened_pairs = 0;         // a video's next frames, or retrieval's neighbours
  int num_pairs_to_screen = 0;          // every pair, or a video's loop candidates
  int num_pairs_kept_by_screening = 0;  // of those, kept by preemptive matching
  int num_pairs = 0;           // pairs matched in full
  int num_verified_pairs = 0;  // pairs with a two-view geometry
  double retrieval_seconds = 0.0;
  double screening_seconds = 0.0;
  double seconds = 0.0;  // all of it
};

// Plans, screens and matches `database`'s pairs and stores their matches and verified geometries
// in it, replacing earlier ones. With `progress`, a line per step.
DatabaseMatchingSummary MatchDatabase(FeatureDatabase* database,
                                      const FeatureMatchingOptions& options,
                                      std::ostream* progress = nullptr);

}  // namespace ramap
