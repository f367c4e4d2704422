// From prior records (a prior file, the database's prior_tx/ty/tz, EXIF GPS) to pose priors
// in one local metric frame: geodetic coordinates go to east-north-up about an origin through
// GeographicLib (io/pose_prior_file.h names the coordinate kinds).
//
// COLMAP 3.8's ImageReader stores EXIF GPS in a database's prior_tx/ty/tz as latitude, longitude
// and altitude, and its model_aligner reads them so (--ref_is_gps 1); a database's priors are read
// the same way unless another PriorCoordinates is given.
#pragma once

#include <string>
#include <vector>

#include "ramap/io/pose_prior_file.h"
#include "ramap/scene/features.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

struct PosePriorOptions {
  PriorCoordinates coordinates = PriorCoordinates::kWgs84;
  // Standard deviations (m) of priors that give none, east/north/up (x/y/z for kXyz): consumer GPS
  // is good to a few metres horizontally and about half as good vertically.
  Eigen::Vector3d std_dev_m = Eigen::Vector3d(3.0, 3.0, 6.0);
  // Origin of the ENU frame. Default: the median latitude, longitude and altitude of the priors
  // (robust to the odd fix on the other side of the planet). Required for kEnu priors to be
  // geodetic (without it they are used as a plain metric frame).
  std::optional<GeodeticPoint> origin;
  // Priors further than this from the origin are rejected as gross errors: an image collection or
  // a drive that spans more than 100 km is not what a local tangent plane is for.
  double max_distance_from_origin_m = 100e3;

  // Throws InputError("PosePrior", ...) on an invalid value.
  void Check() const;
};

struct LocalizedPriors {
  PosePriors priors;
  // One line per record not used (unknown image, NaN, out of range, too far away, duplicate).
  std::vector<std::string> warnings;
  int num_records = 0;
};

// The database's prior_tx/ty/tz of every image that has them (finite or not).
std::vector<PriorRecord> PriorRecordsFromDatabase(const FeatureDatabase& database);

// The coordinates of the database's pose priors as the database states them (COLMAP 3.10 on
// stores a coordinate system with each): kXyz when they say Cartesian and none says WGS84, kWgs84
// when some say WGS84 and none Cartesian; `fallback` when none says, or they disagree (a 3.8
// database stores EXIF GPS as latitude, longitude, altitude without saying so).
PriorCoordinates DatabasePriorCoordinates(const FeatureDatabase& database,
                                          PriorCoordinates fallback);

// Converts `records` into the local frame, keyed by the image ids of `database` (by name). Never
// throws on a bad record: it is skipped with a warning.
LocalizedPriors LocalizePriors(const std::vector<PriorRecord>& records,
                               const FeatureDatabase& database, const PosePriorOptions& options);

// The images of `model` with the prior_tx/ty/tz the database at `database_path` gives the image of
// the same name (none for names it lacks), for matching priors to a model made elsewhere.
FeatureDatabase ModelImagesWithDatabasePriors(const Reconstruction& model,
                                              const std::string& database_path);

}  // namespace ramap
