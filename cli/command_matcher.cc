// `ramap matcher --database_path DB [--Matching.mode sequential|exhaustive]`: matches and verified
// two-view geometries of a database's images (features from ramap feature_extractor), written
// back in COLMAP's schema.
#include <iomanip>
#include <iostream>

#include "feature_options.h"
#include "options.h"
#include "ramap/io/colmap_database.h"

namespace ramap::cli {

DatabaseMatchingSummary MatchAndReport(FeatureDatabase* database, FeatureOptions* options) {
  const DatabaseMatchingSummary summary = MatchDatabase(database, options->matching, &std::cout);
  options->matching.mode = summary.mode;
  options->mode = MatchingModeName(summary.mode);
  std::cout << std::fixed << std::setprecision(2) << "[ramap] matching plan: " << options->mode
            << " (" << summary.reason << "): ";
  const bool retrieval = summary.mode == MatchingMode::kRetrieval;
  if (summary.num_unscreened_pairs > 0 || retrieval) {
    std::cout << summary.num_unscreened_pairs
              << (retrieval ? " retrieved pairs" : " neighbour pairs");
  }
  if (!retrieval) {
    std::cout << (summary.num_unscreened_pairs > 0 ? ", " : "") << summary.num_pairs_to_screen
              << (summary.mode == MatchingMode::kSequential ? " loop candidates" : " pairs");
  }
  if (summary.retrieval_seconds > 0)
    std::cout << " (retrieval " << summary.retrieval_seconds << " s)";
  if (summary.num_pairs_to_screen > 0) {
    std::cout << ", " << summary.num_pairs_kept_by_screening
              << " of them kept by preemptive matching (" << summary.screening_seconds << " s)";
  }
  std::cout << "\n";
  std::cout << "[ramap] matching: " << summary.num_verified_pairs << " of " << summary.num_pairs
            << " pairs verified, " << summary.seconds << " s\n";
  return summary;
}

nlohmann::json MatchingSummaryToJson(const DatabaseMatchingSummary& summary) {
  return {{"mode", MatchingModeName(summary.mode)},
          {"reason", summary.reason},
          {"pairs_matched_unscreened", summary.num_unscreened_pairs},
          {"pairs_to_screen", summary.num_pairs_to_screen},
          {"pairs_kept_by_preemptive_matching", summary.num_pairs_kept_by_screening},
          {"pairs_matched", summary.num_pairs},
          {"pairs_verified", summary.num_verified_pairs},
          {"retrieval_seconds", summary.retrieval_seconds},
          {"preemptive_matching_seconds", summary.screening_seconds},
          {"seconds", summary.seconds}};
}

int RunMatcher(int argc, char** argv) {
  CLI::App app(
      "Matches and verifies image pairs of a COLMAP database written by feature_extractor.",
      "ramap matcher");
  std::string database_path;
  app.add_option("--database_path", database_path, "COLMAP database with descriptors")->required();
  FeatureOptions options;
  AddMatchingOptions(app, &options);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  FinishFeatureOptions(&options);
  DatabaseReadOptions read_options;
  read_options.read_descriptors = true;
  read_options.read_matches = false;
  FeatureDatabase database = ReadColmapDatabase(database_path, read_options);
  MatchAndReport(&database, &options);
  WriteColmapDatabaseMatches(database, database_path);
  std::cout << "Wrote " << database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
