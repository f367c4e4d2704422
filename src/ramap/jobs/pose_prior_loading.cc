#include "ramap/jobs/pose_prior_loading.h"

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
    *log << "[ramap] pose priors: " << priors.priors.by_image.size() << " of " << records.size()
         << " usable (" << (source.path.empty() ? std::string("database") : source.path) << ", "
         << PriorCoordinatesName(options.coordinates) << ")\n";
  }
  return priors;
}

// summary.json's "pose_priors" block, as it was before the priors' options were declared with the
// mapper's (options.PosePrior holds the same values).
nlohmann::json PosePriorOptionsToJson(const PosePriorSource& text, const PriorAlignmentOptions& g) {
  return {{"path", text.path},
          {"type", text.type},
          {"from_database", text.from_database},
          {"origin", text.origin},
          {"std_m", {text.std_x_m, text.std_y_m, text.std_z_m}},
          {"max_distance_from_origin_m", text.max_distance_from_origin_m},
          {"align", g.align},
          {"use_in_translation_averaging", g.use_in_translation_averaging},
          {"use_in_bundle_adjustment", g.use_in_bundle_adjustment},
          {"max_alignment_error_m", g.max_alignment_error_m},
          {"min_num_inliers", g.min_num_inliers},
          {"max_fit_uncertainty_deg", g.max_fit_uncertainty_deg}};
}

}  // namespace ramap
