// `ramap database_info --database_path DB`: what a COLMAP database holds, in counts. Reading it
// runs every check of the reader, so this is also the quickest way to validate a database.
#include <CLI/CLI.hpp>
#include <array>
#include <iostream>
#include <map>
#include <string>

#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/database_rigs_priors.h"

namespace ramap::cli {
namespace {

// COLMAP's names of TwoViewGeometry::ConfigurationType, by value.
constexpr std::array<const char*, 10> kConfigNames = {
    "UNDEFINED", "DEGENERATE",          "CALIBRATED", "UNCALIBRATED", "PLANAR",
    "PANORAMIC", "PLANAR_OR_PANORAMIC", "WATERMARK",  "MULTIPLE",     "CALIBRATED_RIG"};

struct DatabaseInfoCommand {
  std::string database_path;
};

const OptionTable<DatabaseInfoCommand>& DatabaseInfoCommandTable() {
  static const OptionTable<DatabaseInfoCommand> table = {Required(PathOption<DatabaseInfoCommand>(
      "database_path", [](auto& o) -> auto& { return o.database_path; },
      "COLMAP database (SQLite)"))};
  return table;
}

}  // namespace

std::string DatabaseInfoOptionsMarkdown() {
  return OptionTableMarkdown(DatabaseInfoCommandTable(), DatabaseInfoCommand());
}

int RunDatabaseInfo(int argc, char** argv) {
  CLI::App app("Counts what a COLMAP database (3.8 to 4.x) holds, checking it on the way.",
               "ramap database_info");
  DatabaseInfoCommand command;
  if (const auto code = ParseCommandLine(app, DatabaseInfoCommandTable(), &command, argc, argv))
    return *code;
  const std::string& database_path = command.database_path;

  DatabaseReadOptions options;
  options.read_descriptors = true;
  const FeatureDatabase database = ReadColmapDatabase(database_path, options);

  const DatabaseCounts c = CountDatabase(database);
  const RigSummary rigs = SummarizeRigs(database);
  std::cout << "Database: " << database_path << "\n"
            << "  schema:                  " << DatabaseGenerationLabel(database.generation) << "\n"
            << "  cameras:                 " << database.cameras.size() << "\n"
            << "  rigs, frames:            " << rigs.num_rigs << ", " << rigs.num_frames << " ("
            << rigs.num_multi_camera_frames << " with images of several cameras)\n"
            << "  images:                  " << database.images.size() << "\n"
            << "  keypoints:               " << c.num_keypoints << " in "
            << database.keypoints.size() << " images\n"
            << "  descriptors:             " << c.num_descriptors << " in "
            << database.descriptors.size() << " images\n"
            << "  pairs with matches:      " << c.num_pairs_with_matches << " (" << c.num_matches
            << " matches)\n"
            << "  verified pairs:          " << c.num_verified_pairs << " (" << c.num_inliers
            << " inlier matches)\n";
  for (const auto& [config, count] : c.verified_pairs_by_config) {
    std::cout << "    " << kConfigNames.at(static_cast<int>(config)) << ": " << count << "\n";
  }
  std::cout << "  pose priors:         " << c.num_pose_priors
            << " images (GPS from EXIF as latitude, longitude, altitude)\n"
            << "  rotation priors:         " << c.num_rotation_priors << " images\n"
            << "  descriptor ratios:       " << c.num_pairs_with_ratios
            << " verified pairs (ramap's ramap_match_confidence table)\n";
  return 0;
}

}  // namespace ramap::cli
