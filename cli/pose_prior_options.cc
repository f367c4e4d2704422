#include "pose_prior_options.h"

#include <iomanip>

#include "options.h"
#include "ramap/geometry/geodetic.h"
#include "ramap/io/pose_prior_file.h"
#include "ramap/util/error.h"

namespace ramap::cli {

void AddPosePriorOptions(CLI::App& app, PosePriorOptionText* text,
                         GeoregistrationOptions* georegistration, bool with_uses) {
  app.add_option("--PosePrior.path", text->path,
                 "prior file: NAME V1 V2 V3 [SX SY SZ] per line (default: the database's "
                 "prior_tx/ty/tz, where COLMAP stores EXIF GPS)");
  app.add_option("--PosePrior.type", text->type,
                 "auto (the database's priors: as it says, COLMAP 3.10 on; else wgs84) | wgs84 "
                 "(lat lon alt) | enu (m, about --PosePrior.origin) | ecef (m) | xyz (any metric "
                 "frame)")
      ->capture_default_str();
  app.add_option("--PosePrior.from_database", text->from_database,
                 "without --PosePrior.path: 1 uses the database's prior positions")
      ->capture_default_str();
  app.add_option("--PosePrior.origin", text->origin,
                 "lat,lon,alt of the ENU frame (default: the median of the priors)");
  app.add_option("--PosePrior.std_x_m", text->std_x_m, "standard deviation east (or x), m")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--PosePrior.std_y_m", text->std_y_m, "standard deviation north (or y), m")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--PosePrior.std_z_m", text->std_z_m, "standard deviation up (or z), m")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--PosePrior.max_distance_from_origin_m", text->max_distance_from_origin_m,
                 "priors further away are rejected as gross errors")
      ->capture_default_str();
  app.add_option("--PosePrior.max_alignment_error_m", georegistration->max_alignment_error_m,
                 "RANSAC inlier threshold, m (0: 3 x the priors' median 3D standard deviation)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--PosePrior.max_fit_uncertainty_deg", georegistration->max_fit_uncertainty_deg,
                 "priors too close together for their noise (about sigma / (spread sqrt N)) "
                 "leave the model unregistered")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--PosePrior.min_num_inliers", georegistration->min_num_inliers)
      ->capture_default_str()
      ->check(AtLeast(3));
  if (!with_uses) return;
  app.add_option("--PosePrior.align", georegistration->align,
                 "1: georegister each model to its priors (0 ignores the priors)")
      ->capture_default_str();
  app.add_option("--PosePrior.use_in_translation_averaging",
                 georegistration->use_in_translation_averaging,
                 "1: priors as weak rows of translation averaging (fixes scale drift)")
      ->capture_default_str();
  app.add_option("--PosePrior.use_in_bundle_adjustment", georegistration->use_in_bundle_adjustment,
                 "1: priors as residuals of the bundle adjustment (--Mapper.refine 1)")
      ->capture_default_str();
}

LocalizedPriors LoadPosePriors(const PosePriorOptionText& text, const FeatureDatabase& database,
                               const std::string& command, std::ostream& log) {
  PosePriorOptions options;
  const bool from_database = text.path.empty() && text.from_database;
  options.coordinates =
      text.type != "auto" ? PriorCoordinatesFromName(text.type, "--PosePrior.type")
      : from_database     ? DatabasePriorCoordinates(database, PriorCoordinates::kWgs84)
                          : PriorCoordinates::kWgs84;
  options.std_dev_m = Eigen::Vector3d(text.std_x_m, text.std_y_m, text.std_z_m);
  if (!text.origin.empty()) options.origin = ParseGeodeticPoint(text.origin, "--PosePrior.origin");
  options.max_distance_from_origin_m = text.max_distance_from_origin_m;
  options.Check();
  std::vector<PriorRecord> records;
  if (!text.path.empty()) {
    records = ReadPriorFile(text.path);
  } else if (from_database) {
    records = PriorRecordsFromDatabase(database);
  }
  LocalizedPriors priors = LocalizePriors(records, database, options);
  for (size_t k = 0; k < priors.warnings.size() && k < 10; ++k) {
    log << command << ": warning: " << priors.warnings[k] << "\n";
  }
  if (priors.warnings.size() > 10) {
    log << command << ": warning: ... and " << priors.warnings.size() - 10
        << " more priors not used\n";
  }
  if (!records.empty()) {
    log << "[ramap] position priors: " << priors.priors.by_image.size() << " of " << records.size()
        << " usable (" << (text.path.empty() ? std::string("database") : text.path) << ", "
        << PriorCoordinatesName(options.coordinates) << ")\n";
  }
  return priors;
}

nlohmann::json PosePriorOptionsToJson(const PosePriorOptionText& text,
                                      const GeoregistrationOptions& g) {
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

}  // namespace ramap::cli
