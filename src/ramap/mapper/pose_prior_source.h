// Where the mapper's pose priors come from: a prior file, or the database's prior positions (where
// COLMAP stores EXIF GPS), with the noise and range assumed of them: the --PosePrior.* source
// options. The jobs read them (jobs/pose_prior_loading.h); the mapper takes them loaded.
#pragma once

#include <string>

#include "ramap/util/option_table.h"

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

// Its options (--PosePrior.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<PosePriorSource>& PosePriorSourceOptionTable();

}  // namespace ramap
