// Where the mapper's pose priors come from (a prior file or the database's prior positions,
// where COLMAP stores EXIF GPS) and how they are read into the images' local frame: the
// --PosePrior.* source options, shared by the command line and Python.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "ramap/pipeline/pose_priors.h"
#include "ramap/pipeline/prior_alignment.h"
#include "ramap/scene/features.h"

namespace ramap {

struct PosePriorSource {
  std::string path;  // prior file; empty: the database's prior_tx/ty/tz
  // auto: as the database says its priors are (wgs84 or xyz), else wgs84.
  std::string type = "auto";
  std::string origin;  // "lat,lon,alt"; empty: the median of the priors
  bool from_database = true;
  double std_x_m = 3.0, std_y_m = 3.0, std_z_m = 6.0;
  double max_distance_from_origin_m = 100e3;
};

// The priors `source` names, in the local frame of `database`'s images: the file's when a path is
// given, else the database's (unless from_database is off). Skipped records are written to `log`
// as warnings prefixed by `command` (ten at most, then a count); nothing when `log` is null.
LocalizedPriors LoadPosePriors(const PosePriorSource& source, const FeatureDatabase& database,
                               const std::string& command, std::ostream* log);

// The source and the prior alignment settings as summary.json's "pose_priors" block.
nlohmann::json PosePriorOptionsToJson(const PosePriorSource& source,
                                      const PriorAlignmentOptions& prior_alignment);

}  // namespace ramap
