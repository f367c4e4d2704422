#include "ramap/geometry/geodetic.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>
#include <sstream>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// The local frame's conversions, built on each call: GeographicLib::LocalCartesian is cheap to
// construct (a rotation matrix) and keeping one per frame would make the class non-copyable.
GeographicLib::LocalCartesian Cartesian(const GeodeticPoint& origin) {
  return GeographicLib::LocalCartesian(origin.latitude_deg, origin.longitude_deg, origin.altitude_m,
                                       GeographicLib::Geocentric::WGS84());
}

}  // namespace

bool IsValidGeodeticPoint(const GeodeticPoint& point) {
  return std::isfinite(point.latitude_deg) && std::isfinite(point.longitude_deg) &&
         std::isfinite(point.altitude_m) && std::abs(point.latitude_deg) <= 90.0 &&
         point.longitude_deg >= -180.0 && point.longitude_deg < 360.0 &&
         std::abs(point.altitude_m) <= 1e5;
}

GeodeticPoint ParseGeodeticPoint(const std::string& text, const std::string& option) {
  std::istringstream in(text);
  GeodeticPoint point;
  char comma1 = 0, comma2 = 0;
  in >> point.latitude_deg >> comma1 >> point.longitude_deg >> comma2 >> point.altitude_m;
  std::string rest;
  if (in.fail() || comma1 != ',' || comma2 != ',' || (in >> rest)) {
    throw InputError(option, "'" + text + "' is not 'latitude,longitude,altitude'");
  }
  if (!IsValidGeodeticPoint(point)) {
    throw InputError(option, "'" + text +
                                 "' is out of range (latitude in [-90, 90], longitude in "
                                 "[-180, 360), altitude within 100 km)");
  }
  return point;
}

Eigen::Vector3d GeodeticToEcef(const GeodeticPoint& point) {
  Eigen::Vector3d ecef;
  GeographicLib::Geocentric::WGS84().Forward(point.latitude_deg, point.longitude_deg,
                                             point.altitude_m, ecef.x(), ecef.y(), ecef.z());
  return ecef;
}

GeodeticPoint EcefToGeodetic(const Eigen::Vector3d& ecef) {
  GeodeticPoint point;
  GeographicLib::Geocentric::WGS84().Reverse(ecef.x(), ecef.y(), ecef.z(), point.latitude_deg,
                                             point.longitude_deg, point.altitude_m);
  return point;
}

LocalEnuFrame::LocalEnuFrame(const GeodeticPoint& origin) : origin_(origin) {}

Eigen::Vector3d LocalEnuFrame::FromGeodetic(const GeodeticPoint& point) const {
  Eigen::Vector3d enu;
  Cartesian(origin_).Forward(point.latitude_deg, point.longitude_deg, point.altitude_m, enu.x(),
                             enu.y(), enu.z());
  return enu;
}

GeodeticPoint LocalEnuFrame::ToGeodetic(const Eigen::Vector3d& enu) const {
  GeodeticPoint point;
  Cartesian(origin_).Reverse(enu.x(), enu.y(), enu.z(), point.latitude_deg, point.longitude_deg,
                             point.altitude_m);
  return point;
}

Eigen::Vector3d LocalEnuFrame::FromEcef(const Eigen::Vector3d& ecef) const {
  return FromGeodetic(EcefToGeodetic(ecef));
}

Eigen::Vector3d LocalEnuFrame::ToEcef(const Eigen::Vector3d& enu) const {
  return GeodeticToEcef(ToGeodetic(enu));
}

}  // namespace ramap
