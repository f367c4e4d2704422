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

  size_t num_keypoints = 0;
  for (const auto& [image_id, keypoints] : database.keypoints) num_keypoints += keypoints.size();
  size_t num_descriptors = 0;
  for (const auto& [image_id, descriptors] : database.descriptors) {
    num_descriptors += descriptors.size();
  }
  size_t num_pairs_with_matches = 0;
  size_t num_matches = 0;
  for (const auto& [pair_id, matches] : database.matches) {
    num_pairs_with_matches += matches.empty() ? 0 : 1;
    num_matches += matches.size();
  }
  std::map<int, size_t> pairs_by_config;
  size_t num_verified_pairs = 0;
  size_t num_inliers = 0;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (geometry.inlier_matches.empty()) continue;
    ++num_verified_pairs;
    num_inliers += geometry.inlier_matches.size();
    ++pairs_by_config[static_cast<int>(geometry.config)];
  }

  std::cout << "Database: " << database_path << "\n"
            << "  cameras:                 " << database.cameras.size() << "\n"
            << "  images:                  " << database.images.size() << "\n"
            << "  keypoints:               " << num_keypoints << " in " << database.keypoints.size()
            << " images\n"
            << "  descriptors:             " << num_descriptors << " in "
            << database.descriptors.size() << " images\n"
            << "  pairs with matches:      " << num_pairs_with_matches << " (" << num_matches
            << " matches)\n"
            << "  verified pairs:          " << num_verified_pairs << " (" << num_inliers
            << " inlier matches)\n";
  for (const auto& [config, count] : pairs_by_config) {
    std::cout << "    " << kConfigNames.at(config) << ": " << count << "\n";
  }
  size_t num_position_priors = 0, num_rotation_priors = 0, num_pairs_with_ratios = 0;
  for (const auto& [image_id, image] : database.images) {
    num_position_priors += image.prior_translation ? 1 : 0;
    num_rotation_priors += image.prior_rotation ? 1 : 0;
  }
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    num_pairs_with_ratios += geometry.inlier_ratios.empty() ? 0 : 1;
  }
  std::cout << "  position priors:         " << num_position_priors
            << " images (prior_tx/ty/tz; GPS from EXIF as latitude, longitude, altitude)\n"
            << "  rotation priors:         " << num_rotation_priors << " images\n"
            << "  descriptor ratios:       " << num_pairs_with_ratios
            << " verified pairs (ramap's ramap_match_confidence table)\n";
  return 0;
}

}  // namespace ramap::cli
