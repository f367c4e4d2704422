#include <string>
#include <utility>
#include <vector>

#include "ramap/estimators/track_triangulation.h"

namespace ramap {

namespace {

using Table = OptionTable<TrackTriangulationOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<TrackTriangulationOptions>(
      "Triangulation.max_reprojection_error_px",
      [](auto& o) -> auto& { return o.max_reprojection_error_px; }, Above(0),
      "observations farther from their point are not kept"));
  t.push_back(NumberOption<TrackTriangulationOptions>(
      "Triangulation.min_triangulation_angle_deg",
      [](auto& o) -> auto& { return o.min_triangulation_angle_deg; }, AtLeast(0, 90),
      "points seen under a smaller angle are not kept"));
  t.push_back(NumberOption<TrackTriangulationOptions>(
      "Triangulation.start_max_error_deg", [](auto& o) -> auto& { return o.start_max_error_deg; },
      AtLeast(0, 89),
      "where the points start bundle adjustment, observations farther from their point than "
      "this angle are not kept (0: Triangulation.max_reprojection_error_px)"));
}

}  // namespace

const OptionTable<TrackTriangulationOptions>& TrackTriangulationOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
