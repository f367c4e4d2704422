// Images to a model as a user asks for it: features into a new COLMAP database, matching by the
// plan the options choose, the mapper (with loop closure after sequential matching), models
// written. `ramap feature_extractor`, `matcher` and `reconstruct` and Python's
// ramap.extract_features, match and reconstruct are these functions.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "ramap/features/matching_plan.h"
#include "ramap/jobs/reconstruct_options.h"
#include "ramap/mapper/mapper.h"

namespace ramap {

// The features of the images in `image_path` (all, or those `image_list` names), with one line
// to `progress` and a warning per unreadable image to `warnings` (when given), and what it found
// in `extraction` (when given). Throws InputError when no image could be read.
FeatureDatabase ExtractFeatures(const std::string& image_path, const std::string& image_list,
                                const FeatureOptions& options, std::ostream* progress,
                                std::ostream* warnings, ExtractionSummary* extraction = nullptr);

// Matches and verifies the pairs the plan chooses; options->matching.mode becomes the mode that
// ran (auto resolved).
DatabaseMatchingSummary MatchFeatures(FeatureDatabase* database, FeatureOptions* options,
                                      std::ostream* progress);

nlohmann::json MatchingSummaryToJson(const DatabaseMatchingSummary& summary);

// `ramap feature_extractor`: options resolved, the new database's path checked (refused when it
// exists or is an input), the features extracted and written there. Returns how many images.
size_t ExtractFeaturesToDatabase(const std::string& image_path, const std::string& image_list,
                                 const std::string& database_path, FeatureOptions options,
                                 std::ostream* progress, std::ostream* warnings);

// `ramap matcher`: options resolved, the database's descriptors read, its pairs matched and
// verified, the matches written back.
DatabaseMatchingSummary MatchDatabaseFile(const std::string& database_path, FeatureOptions options,
                                          std::ostream* progress);

struct ReconstructJob {
  std::string image_path;
  std::string image_list;   // optional: only these images (names relative to image_path)
  std::string output_path;  // database.db and sparse/ (models 0, 1, ... and summary.json)
  ReconstructOptions options;
  std::string command = "ramap reconstruct";  // what warnings are prefixed with
};

struct ReconstructResult {
  MapperResult mapping;
  size_t num_images = 0;  // images whose features were extracted
};

// The whole run. What it creates is removed again when it fails or is stopped; an existing
// output folder is kept, with nothing of this run in it.
ReconstructResult RunReconstructJob(const ReconstructJob& job, std::ostream* progress,
                                    std::ostream* warnings);

}  // namespace ramap
