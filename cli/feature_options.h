// The options of image-list input on the command line, COLMAP-style (--ImageReader.*,
// --FeatureExtraction.*, --Matching.*), shared by feature_extractor, matcher and reconstruct.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "ramap/features/feature_matching.h"
#include "ramap/features/image_reader.h"
#include "ramap/features/matching_plan.h"
#include "ramap/scene/features.h"

namespace ramap::cli {

struct FeatureOptions {
  ImageReaderOptions reader;
  FeatureExtractionOptions extraction;
  FeatureMatchingOptions matching;
  std::string type = FeatureTypeName(FeatureExtractionOptions().type);
  std::string mode = MatchingModeName(FeatureMatchingOptions().mode);
  // The generation of the database written (3.8: read by every COLMAP, 4.x upgrades it).
  std::string generation_name = "3.8";
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
};

void AddExtractionOptions(CLI::App& app, FeatureOptions* options);
void AddMatchingOptions(CLI::App& app, FeatureOptions* options);
// Converts the enum options and checks them; throws InputError naming the option.
void FinishFeatureOptions(FeatureOptions* options);

// The steps of feature_extractor and matcher, with their report lines, shared with reconstruct.
// ExtractAndReport throws InputError when no image could be read.
FeatureDatabase ExtractAndReport(const std::string& image_path, const std::string& image_list,
                                 const FeatureOptions& options);
// Matches as --Matching.mode says and prints the plan and its counts; `options` is left with the
// mode auto stood for, so that what follows (reconstruct's loop closure) knows it.
DatabaseMatchingSummary MatchAndReport(FeatureDatabase* database, FeatureOptions* options);
// The plan and its counts for summary.json.
nlohmann::json MatchingSummaryToJson(const DatabaseMatchingSummary& summary);

}  // namespace ramap::cli
