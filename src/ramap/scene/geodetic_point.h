// A point on the earth in WGS84 coordinates, as GPS and survey files give it (the conversions are
// geometry/geodetic.h's).
#pragma once

namespace ramap {

struct GeodeticPoint {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;  // above the WGS84 ellipsoid
};

}  // namespace ramap
