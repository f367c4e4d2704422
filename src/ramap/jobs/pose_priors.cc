#include "ramap/jobs/pose_priors.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "ramap/geometry/geodetic.h"
#include "ramap/io/colmap_database.h"
#include "ramap/util/error.h"
#include "ramap/util/statistics.h"

namespace ramap {
namespace {

bool ValidDeviations(const Eigen::Vector3d& std_dev_m) {
  return std_dev_m.allFinite() && std_dev_m.minCoeff() > 0;
}

std::string Vector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(10) << v.x() << " " << v.y() << " " << v.z();
  return out.str();
}

// Why a record's value cannot be used, or "" when it can.
std::string ValueProblem(const PriorRecord& record, PriorCoordinates coordinates) {
  if (!record.value.allFinite()) return "not a finite value (" + Vector(record.value) + ")";
  if (coordinates == PriorCoordinates::kWgs84 &&
      !IsValidGeodeticPoint({record.value.x(), record.value.y(), record.value.z()})) {
    return "not a latitude, longitude, altitude (" + Vector(record.value) + ")";
  }
  if (coordinates == PriorCoordinates::kEcef) {
    const double radius = record.value.norm();  // the Earth's radius is 6357 - 6378 km
    if (radius < 6.25e6 || radius > 6.48e6) {
      return "not an earth-centred position (" + std::to_string(radius / 1e3) +
             " km from the centre of the Earth)";
    }
  }
  return "";
}

}  // namespace

void PosePriorOptions::Check() const {
  if (!ValidDeviations(std_dev_m)) {
    throw InputError("PosePriorOptions::std_dev_m", "each must be finite and > 0");
  }
  if (origin && !IsValidGeodeticPoint(*origin)) {
    throw InputError("--PosePrior.origin", "out of range");
  }
  if (!(max_distance_from_origin_m > 0)) {
    throw InputError("PosePriorOptions::max_distance_from_origin_m", "must be > 0");
  }
}

std::vector<PriorRecord> PriorRecordsFromDatabase(const FeatureDatabase& database) {
  std::vector<PriorRecord> records;
  for (const auto& [id, image] : database.images) {
    if (!image.prior_translation) continue;
    PriorRecord record;
    record.image_name = image.name;
    record.value = *image.prior_translation;
    record.where = "database, image " + std::to_string(id);
    // COLMAP 3.11 on stores the prior's covariance (m^2); its diagonal gives the deviations.
    if (image.prior_position_covariance) {
      const Eigen::Vector3d variances = image.prior_position_covariance->diagonal();
      if (variances.allFinite() && variances.minCoeff() > 0) {
        record.std_dev_m = variances.cwiseSqrt();
      }
    }
    records.push_back(record);
  }
  return records;
}

PriorCoordinates DatabasePriorCoordinates(const FeatureDatabase& database,
                                          PriorCoordinates fallback) {
  bool wgs84 = false, cartesian = false;
  for (const auto& [id, image] : database.images) {
    if (!image.prior_translation) continue;
    wgs84 |= image.prior_coordinate_system == PriorCoordinateSystem::kWgs84;
    cartesian |= image.prior_coordinate_system == PriorCoordinateSystem::kCartesian;
  }
  if (wgs84 == cartesian) return fallback;
  return cartesian ? PriorCoordinates::kXyz : PriorCoordinates::kWgs84;
}

namespace {

// The local east-north-up frame: about the given origin, or for geodetic and ECEF priors about
// their median; none for priors already in a metric frame without an origin.
std::optional<LocalEnuFrame> LocalFrame(const std::map<uint32_t, const PriorRecord*>& usable,
                                        const PosePriorOptions& options) {
  if (options.origin) return LocalEnuFrame(*options.origin);
  if (options.coordinates != PriorCoordinates::kWgs84 &&
      options.coordinates != PriorCoordinates::kEcef) {
    return std::nullopt;
  }
  std::vector<Eigen::Vector3d> values;
  for (const auto& [id, record] : usable) values.push_back(record->value);
  const Eigen::Vector3d median = MedianPoint(values);
  return LocalEnuFrame(options.coordinates == PriorCoordinates::kWgs84
                           ? GeodeticPoint{median.x(), median.y(), median.z()}
                           : EcefToGeodetic(median));
}

// Each usable prior's position in the local frame.
std::map<uint32_t, Eigen::Vector3d> LocalPositions(
    const std::map<uint32_t, const PriorRecord*>& usable, const std::optional<LocalEnuFrame>& frame,
    const PosePriorOptions& options) {
  std::map<uint32_t, Eigen::Vector3d> local;
  for (const auto& [id, record] : usable) {
    const Eigen::Vector3d& v = record->value;
    switch (options.coordinates) {
      case PriorCoordinates::kWgs84:
        local[id] = frame->FromGeodetic({v.x(), v.y(), v.z()});
        break;
      case PriorCoordinates::kEcef:
        local[id] = frame->FromEcef(v);
        break;
      case PriorCoordinates::kEnu:
      case PriorCoordinates::kXyz:
        local[id] = v;
        break;
    }
  }
  return local;
}

}  // namespace

LocalizedPriors LocalizePriors(const std::vector<PriorRecord>& records,
                               const FeatureDatabase& database, const PosePriorOptions& options) {
  options.Check();
  LocalizedPriors result;
  result.num_records = static_cast<int>(records.size());
  std::map<std::string, uint32_t> ids;
  for (const auto& [id, image] : database.images) ids[image.name] = id;
  auto warn = [&](const PriorRecord& record, const std::string& problem) {
    result.warnings.push_back(record.where + ": prior of " + record.image_name +
                              " not used: " + problem);
  };

  // Usable records, one per image.
  std::map<uint32_t, const PriorRecord*> usable;
  for (const PriorRecord& record : records) {
    const auto id = ids.find(record.image_name);
    if (id == ids.end()) {
      warn(record, "no image of that name in the database");
      continue;
    }
    if (const std::string problem = ValueProblem(record, options.coordinates); !problem.empty()) {
      warn(record, problem);
      continue;
    }
    if (record.std_dev_m && !ValidDeviations(*record.std_dev_m)) {
      warn(record, "standard deviations must be finite and > 0");
      continue;
    }
    if (!usable.emplace(id->second, &record).second) warn(record, "a second prior for the image");
  }
  if (usable.empty()) return result;

  const std::optional<LocalEnuFrame> frame = LocalFrame(usable, options);
  if (frame && options.coordinates != PriorCoordinates::kXyz) {
    result.priors.origin = frame->origin();
  }
  const std::map<uint32_t, Eigen::Vector3d> local = LocalPositions(usable, frame, options);
  // Gross errors: too far from the origin (for local frames without one, the median position).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  if (!result.priors.origin) {
    std::vector<Eigen::Vector3d> positions;
    for (const auto& [id, p] : local) positions.push_back(p);
    centre = MedianPoint(positions);
  }
  for (const auto& [id, position] : local) {
    const double distance = (position - centre).norm();
    if (distance > options.max_distance_from_origin_m) {
      std::ostringstream problem;
      problem << std::fixed << std::setprecision(1) << distance / 1e3
              << " km from the origin of the local frame (PosePrior.max_distance_from_origin_m "
              << options.max_distance_from_origin_m / 1e3 << " km)";
      warn(*usable.at(id), problem.str());
      continue;
    }
    const PriorRecord& record = *usable.at(id);
    result.priors.by_image[id] = {position, record.std_dev_m.value_or(options.std_dev_m)};
  }
  return result;
}

FeatureDatabase ModelImagesWithDatabasePriors(const Reconstruction& model,
                                              const std::string& database_path) {
  DatabaseReadOptions read_options;
  read_options.read_matches = false;
  const FeatureDatabase database = ReadColmapDatabase(database_path, read_options);
  std::map<std::string, const Image*> by_name;
  for (const auto& [id, image] : database.images) by_name[image.name] = &image;
  FeatureDatabase images;
  for (const auto& [id, image] : model.images) {
    Image copy = image;
    const auto found = by_name.find(image.name);
    if (found != by_name.end()) copy.prior_translation = found->second->prior_translation;
    images.images[id] = copy;
  }
  return images;
}

}  // namespace ramap
