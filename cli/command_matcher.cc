// `ramap matcher --database_path DB [--Matching.mode sequential|exhaustive]`: matches and verified
// two-view geometries of a database's images (features from ramap feature_extractor), written
// back in COLMAP's schema.
#include <iomanip>
#include <iostream>

#include "feature_options.h"
#include "options.h"
#include "ramap/io/colmap_database.h"

namespace ramap::cli {

void MatchAndReport(FeatureDatabase* database, FeatureOptions* options) {
  // The mode auto stands for, so that what follows (reconstruct's loop closure) knows it.
  options->matching.mode = ResolveMatchingMode(options->matching, *database);
  options->mode = MatchingModeName(options->matching.mode);
  const MatchingSummary summary = MatchDatabase(database, options->matching, &std::cout);
  std::cout << "[ramap] matching: " << summary.num_verified_pairs << " of " << summary.num_pairs
            << " pairs verified (" << options->mode;
  if (summary.num_preemptive_pairs > 0) {
    std::cout << ", " << summary.num_pairs << " of " << summary.num_preemptive_pairs
              << " kept by preemptive matching";
  }
  std::cout << "), " << std::fixed << std::setprecision(2) << summary.seconds << " s\n";
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
