#include "ramap/mapper/pose_prior_source.h"

#include <string>
#include <utility>
#include <vector>

namespace ramap {

namespace {

using Table = OptionTable<PosePriorSource>;

void Declare(Table& t) {
  t.push_back(TextOption<PosePriorSource>(
      "PosePrior.path", [](auto& o) -> auto& { return o.path; },
      "prior file: NAME V1 V2 V3 [SX SY SZ] per line (empty: the database's prior_tx/ty/tz, "
      "where COLMAP stores EXIF GPS)"));
  t.push_back(ChoiceOption<PosePriorSource>(
      "PosePrior.type", [](auto& o) -> auto& { return o.type; },
      std::vector<std::pair<std::string, std::string>>{
          {"auto", "auto"}, {"wgs84", "wgs84"}, {"enu", "enu"}, {"ecef", "ecef"}, {"xyz", "xyz"}},
      "auto: as the database says (COLMAP 3.10 on), else wgs84 (lat lon alt); enu: "
      "m about PosePrior.origin; ecef: m; xyz: any metric frame"));
  t.push_back(BoolOption<PosePriorSource>(
      "PosePrior.from_database", [](auto& o) -> auto& { return o.from_database; },
      "without PosePrior.path: 1 uses the database's prior positions"));
  t.push_back(TextOption<PosePriorSource>(
      "PosePrior.origin", [](auto& o) -> auto& { return o.origin; },
      "lat,lon,alt of the ENU frame (empty: the median of the priors)"));
  t.push_back(NumberOption<PosePriorSource>(
      "PosePrior.std_x_m", [](auto& o) -> auto& { return o.std_x_m; }, Above(0),
      "standard deviation east (or x), m"));
  t.push_back(NumberOption<PosePriorSource>(
      "PosePrior.std_y_m", [](auto& o) -> auto& { return o.std_y_m; }, Above(0),
      "standard deviation north (or y), m"));
  t.push_back(NumberOption<PosePriorSource>(
      "PosePrior.std_z_m", [](auto& o) -> auto& { return o.std_z_m; }, Above(0),
      "standard deviation up (or z), m"));
  t.push_back(NumberOption<PosePriorSource>(
      "PosePrior.max_distance_from_origin_m",
      [](auto& o) -> auto& { return o.max_distance_from_origin_m; }, Above(0),
      "priors further away are rejected as gross errors"));
}

}  // namespace

const OptionTable<PosePriorSource>& PosePriorSourceOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
