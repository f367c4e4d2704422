// --PosePrior.* options, shared by the commands that georegister (mapper, reconstruct,
// model_aligner): where the priors come from, their coordinates and accuracy, and what the mapper
// does with them (MapperOptions::georegistration).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "ramap/pipeline/georegistration.h"
#include "ramap/pipeline/mapper.h"
#include "ramap/pipeline/pose_priors.h"

namespace ramap::cli {

struct PosePriorOptionText {
  std::string path;  // prior file; empty: the database's prior_tx/ty/tz
  // auto: as the database says its priors are (wgs84 or xyz), else wgs84.
  std::string type = "auto";
  std::string origin;  // "lat,lon,alt"; empty: the median of the priors
  bool from_database = true;
  double std_x_m = 3.0, std_y_m = 3.0, std_z_m = 6.0;
  double max_distance_from_origin_m = 100e3;
};

// `with_uses`: also --PosePrior.use_in_translation_averaging / use_in_bundle_adjustment / align
// (the mapper's); model_aligner only aligns.
void AddPosePriorOptions(CLI::App& app, PosePriorOptionText* text,
                         GeoregistrationOptions* georegistration, bool with_uses);

// The priors the options name, in the local frame of `database`'s images: the file's when
// --PosePrior.path is given, else the database's (unless --PosePrior.from_database 0). Skipped
// records are printed to `log` as warnings prefixed by `command` (ten at most, then a count).
LocalizedPriors LoadPosePriors(const PosePriorOptionText& text, const FeatureDatabase& database,
                               const std::string& command, std::ostream& log);

nlohmann::json PosePriorOptionsToJson(const PosePriorOptionText& text,
                                      const GeoregistrationOptions& georegistration);

}  // namespace ramap::cli
