// `ramap matcher --database_path DB [--Matching.mode sequential|exhaustive]`: matches and verified
// two-view geometries of a database's images (features from ramap feature_extractor), written
// back in COLMAP's schema.
#include <iostream>

#include "options.h"
#include "ramap/pipeline/reconstruct_job.h"

namespace ramap::cli {

int RunMatcher(int argc, char** argv) {
  CLI::App app(
      "Matches and verifies image pairs of a COLMAP database written by feature_extractor.",
      "ramap matcher");
  std::string database_path;
  app.add_option("--database_path", database_path, "COLMAP database with descriptors")->required();
  FeatureOptions options;
  AddOptionTable(app, MatchingOptionTable(), &options);
  const LogLevelOption log_level(app);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  MatchDatabaseFile(database_path, options, log_level.progress());
  std::cout << "Wrote " << database_path << "\n";
  return 0;
}

}  // namespace ramap::cli
