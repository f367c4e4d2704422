#include "ramap/pipeline/pose_prior_loading.h"

#include "ramap/geometry/geodetic.h"
#include "ramap/io/pose_prior_file.h"

namespace ramap {

LocalizedPriors LoadPosePriors(const PosePriorSource& source, const FeatureDatabase& database,
                               const std::string& command, std::ostream* log) {
  PosePriorOptions options;
  const bool from_database = source.path.empty() && source.from_database;
  options.coordinates =
      source.type != "auto" ? PriorCoordinatesFromName(source.type, "--PosePrior.type")
      : from_database       ? DatabasePriorCoordinates(database, PriorCoordinates::kWgs84)
                            : PriorCoordinates::kWgs84;
  options.std_dev_m = Eigen::Vector3d(source.std_x_m, source.std_y_m, source.std_z_m);
  if (!source.origin.empty())
    options.origin = ParseGeodeticPoint(source.origin, "--PosePrior.origin");
  options.max_distance_from_origin_m = source.max_distance_from_origin_m;
  options.Check();
  std::vector<PriorRecord> records;
  if (!source.path.empty()) {
    records = ReadPriorFile(source.path);
  } else if (from_database) {
    records = PriorRecordsFromDatabase(database);
  }
  LocalizedPriors priors = LocalizePriors(records, database, options);
  if (log == nullptr) return priors;
  for (size_t k = 0; k < priors.warnings.size() && k < 10; ++k) {
    *log << command << ": warning: " << priors.warnings[k] << "\n";
  }
  if (priors.warnings.size() > 10) {
    *log << command << ": warning: ... and " << priors.warnings.size() - 10
         << " more priors not used\n";
  }
  if (!records.empty()) {
    *log << "[ramap] position priors: " << priors.priors.by_image.size() << " of " << records.size()
         << " usable (" << (source.path.empty() ? std::string("database") : source.path) << ", "
         << PriorCoordinatesName(options.coordinates) << ")\n";
  }
  return priors;
}

}  // namespace ramap
