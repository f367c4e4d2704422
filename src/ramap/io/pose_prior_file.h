// Camera pose priors as a text file, one image a line:
//
//   # comment
//   NAME  V1 V2 V3            (the coordinates, see PriorCoordinates)
//   NAME  V1 V2 V3  S1 S2 S3  (and that prior's standard deviations in metres, east north up or x y
//   z)
//
// NAME is the image name as in the database (no spaces). The reader only parses: a malformed line
// (wrong number of fields, text where a number belongs) throws InputError naming the file and line;
// values that parse but make no sense (NaN, a latitude of 200) are returned as they are, for
// LocalizePriors to report and skip, so one bad fix does not stop a run.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace ramap {

enum class PriorCoordinates {
  kWgs84,  // latitude (deg), longitude (deg), altitude (m) above the WGS84 ellipsoid
  kEnu,    // east, north, up (m) about a known geodetic origin (--PosePrior.origin)
  kEcef,   // earth-centred, earth-fixed x, y, z (m)
  kXyz,    // any metric frame, no geodetic meaning (a survey, a motion-capture system)
};
// "wgs84", "enu", "ecef", "xyz"; throws InputError naming `option` otherwise.
PriorCoordinates PriorCoordinatesFromName(const std::string& name, const std::string& option);
const char* PriorCoordinatesName(PriorCoordinates coordinates);

// One prior as read, before any conversion.
struct PriorRecord {
  std::string image_name;
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> std_dev_m;
  std::string where;  // "FILE:LINE" or "database", for messages
};

std::vector<PriorRecord> ReadPriorFile(const std::string& path);

// Writes records in the same format (staged under a temporary name, then renamed).
void WritePriorFile(const std::vector<PriorRecord>& records, const std::string& path);

}  // namespace ramap
