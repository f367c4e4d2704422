// Geodetic coordinates (WGS84 latitude, longitude, ellipsoidal height) and the local metric frames
// ramap writes models aligned to their priors in. Every conversion is GeographicLib's (Karney's
// exact ellipsoidal formulas); none is written here.
#pragma once

#include <Eigen/Core>
#include <string>

#include "ramap/scene/geodetic_point.h"

namespace ramap {

// Whether the latitude is in [-90, 90], the longitude in [-180, 360) and every value finite (the
// altitude within 100 km of the ellipsoid, which excludes swapped or garbage columns).
bool IsValidGeodeticPoint(const GeodeticPoint& point);

// "lat,lon,alt" as typed on the command line; throws InputError naming `option` when malformed or
// out of range.
GeodeticPoint ParseGeodeticPoint(const std::string& text, const std::string& option);

// Earth-centred, earth-fixed coordinates (metres) of a geodetic point, and back.
Eigen::Vector3d GeodeticToEcef(const GeodeticPoint& point);
GeodeticPoint EcefToGeodetic(const Eigen::Vector3d& ecef);

// East-north-up coordinates (metres) about a fixed origin: GeographicLib::LocalCartesian.
class LocalEnuFrame {
 public:
  explicit LocalEnuFrame(const GeodeticPoint& origin);
  const GeodeticPoint& origin() const { return origin_; }

  Eigen::Vector3d FromGeodetic(const GeodeticPoint& point) const;
  GeodeticPoint ToGeodetic(const Eigen::Vector3d& enu) const;
  Eigen::Vector3d FromEcef(const Eigen::Vector3d& ecef) const;
  Eigen::Vector3d ToEcef(const Eigen::Vector3d& enu) const;

 private:
  GeodeticPoint origin_;
};

}  // namespace ramap
