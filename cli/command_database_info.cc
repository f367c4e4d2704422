// `ramap database_info --database_path DB`: what a COLMAP database holds, in counts. Reading it
// runs every check of the reader, so this is also the quickest way to validate a database.
#include <CLI/CLI.hpp>
#include <array>
#include <iostream>
#include <map>
#include <string>

#include "options.h"
#include "ramap/io/colmap_database.h"

namespace ramap::cli {
namespace {

// COLMAP's names of TwoViewGeometry::ConfigurationType, by value.
constexpr std::array<const char*, 9> kConfigNames = {
    "UNDEFINED", "DEGENERATE",          "CALIBRATED", "UNCALIBRATED", "PLANAR",
    "PANORAMIC", "PLANAR_OR_PANORAMIC", "WATERMARK",  "MULTIPLE"};

}  // namespace

int RunDatabaseInfo(int argc, char** argv) {
  CLI::App app("Counts what a COLMAP 3.8 database holds, checking it on the way.",
               "ramap database_info");
  std::string database_path;
  app.add_option("--database_path", database_path, "COLMAP database (SQLite)")->required();
  if (const auto exit_code = ParseOptions(app, argc, argv)) return *exit_code;

  DatabaseReadOptions options;
  options.read_descriptors = true;
  const FeatureDatabase database = ReadColmapDatabase(database_path, options);

  const DatabaseCounts c = CountDatabase(database);
  std::cout << "Database: " << database_path << "\n"
            << "  cameras:                 " << database.cameras.size() << "\n"
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
  std::cout << "  position priors:         " << c.num_position_priors
            << " images (prior_tx/ty/tz; GPS from EXIF as latitude, longitude, altitude)\n"
            << "  rotation priors:         " << c.num_rotation_priors << " images\n"
            << "  descriptor ratios:       " << c.num_pairs_with_ratios
            << " verified pairs (ramap's ramap_match_confidence table)\n";
  return 0;
}

}  // namespace ramap::cli
