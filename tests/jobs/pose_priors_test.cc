// Priors from records to the local frame: every kind of bad prior is skipped with a warning that
// names it, and the rest are used.
#include "ramap/jobs/pose_priors.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ramap/geometry/geodetic.h"

namespace ramap {
namespace {

const GeodeticPoint kOrigin{49.011, 8.4165, 115.0};

FeatureDatabase Images(int count) {
  FeatureDatabase database;
  for (int k = 1; k <= count; ++k) {
    Image image;
    image.image_id = k;
    image.name = "image" + std::to_string(k) + ".jpg";
    database.images[k] = image;
  }
  return database;
}

PriorRecord Geodetic(int image, const Eigen::Vector3d& enu, const LocalEnuFrame& frame) {
  const GeodeticPoint p = frame.ToGeodetic(enu);
  return {"image" + std::to_string(image) + ".jpg",
          Eigen::Vector3d(p.latitude_deg, p.longitude_deg, p.altitude_m), std::nullopt,
          "test:" + std::to_string(image)};
}

bool Mentions(const std::vector<std::string>& warnings, const std::string& text) {
  for (const std::string& w : warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(PosePriors, Wgs84AboutTheMedianOriginWithBadRecordsSkipped) {
  const LocalEnuFrame frame(kOrigin);
  const FeatureDatabase database = Images(8);
  std::vector<PriorRecord> records;
  for (int k = 1; k <= 5; ++k) records.push_back(Geodetic(k, {10.0 * k, -5.0 * k, 1.0}, frame));
  // Image 6: NaN; image 7: on the other side of the planet; image 8: a latitude of 95 degrees.
  records.push_back({"image6.jpg", Eigen::Vector3d(NAN, 8.4, 115), std::nullopt, "test:6"});
  records.push_back(
      {"image7.jpg", Eigen::Vector3d(-49.011, 8.4165 - 180, 115), std::nullopt, "test:7"});
  records.push_back({"image8.jpg", Eigen::Vector3d(95, 8.4, 115), std::nullopt, "test:8"});
  records.push_back({"unknown.jpg", Eigen::Vector3d(49, 8, 100), std::nullopt, "test:9"});
  records.push_back(Geodetic(1, {0, 0, 0}, frame));  // a second prior for image 1
  PosePriorOptions options;
  const LocalizedPriors priors = LocalizePriors(records, database, options);
  EXPECT_EQ(priors.num_records, 10);
  ASSERT_EQ(priors.priors.by_image.size(), 5u);
  ASSERT_EQ(priors.warnings.size(), 5u);
  EXPECT_TRUE(Mentions(priors.warnings, "test:6: prior of image6.jpg not used: not a finite"));
  EXPECT_TRUE(Mentions(priors.warnings, "test:7: prior of image7.jpg not used: 12"));  // ~12,700 km
  EXPECT_TRUE(Mentions(priors.warnings, "test:8: prior of image8.jpg not used: not a latitude"));
  EXPECT_TRUE(Mentions(priors.warnings, "no image of that name"));
  EXPECT_TRUE(Mentions(priors.warnings, "a second prior"));
  // The origin is the median fix (image 3), so the local positions are the ENU ones minus its.
  ASSERT_TRUE(priors.priors.origin.has_value());
  const Eigen::Vector3d offset = frame.FromGeodetic(*priors.priors.origin);
  EXPECT_LT((offset - Eigen::Vector3d(30, -15, 1)).norm(), 1e-6);
  for (int k = 1; k <= 5; ++k) {
    const PosePrior& prior = priors.priors.by_image.at(k);
    EXPECT_LT((prior.center + offset - Eigen::Vector3d(10.0 * k, -5.0 * k, 1.0)).norm(), 2e-3);
    EXPECT_EQ(prior.std_dev_m, options.std_dev_m);
  }
}

TEST(PosePriors, EcefEnuAndXyzFrames) {
  const LocalEnuFrame frame(kOrigin);
  const FeatureDatabase database = Images(3);
  std::vector<PriorRecord> ecef, enu;
  for (int k = 1; k <= 3; ++k) {
    const Eigen::Vector3d position(5.0 * k, 2.0, -1.0 * k);
    ecef.push_back({"image" + std::to_string(k) + ".jpg", frame.ToEcef(position),
                    Eigen::Vector3d(1, 1, 2), "e"});
    enu.push_back({"image" + std::to_string(k) + ".jpg", position, std::nullopt, "n"});
  }
  PosePriorOptions options;
  options.coordinates = PriorCoordinates::kEcef;
  options.origin = kOrigin;
  const LocalizedPriors from_ecef = LocalizePriors(ecef, database, options);
  ASSERT_EQ(from_ecef.priors.by_image.size(), 3u);
  EXPECT_LT((from_ecef.priors.by_image.at(2).center - Eigen::Vector3d(10, 2, -2)).norm(), 1e-3);
  EXPECT_EQ(from_ecef.priors.by_image.at(2).std_dev_m, Eigen::Vector3d(1, 1, 2));
  options.coordinates = PriorCoordinates::kEnu;
  const LocalizedPriors from_enu = LocalizePriors(enu, database, options);
  EXPECT_EQ(from_enu.priors.by_image.at(3).center, Eigen::Vector3d(15, 2, -3));
  EXPECT_TRUE(from_enu.priors.origin.has_value());
  options.coordinates = PriorCoordinates::kXyz;
  const LocalizedPriors from_xyz = LocalizePriors(enu, database, options);
  EXPECT_FALSE(from_xyz.priors.origin.has_value());  // no geodetic meaning, no GeoJSON
  // An earth-centred value that is not on the Earth.
  ecef[0].value = Eigen::Vector3d(1, 2, 3);
  options.coordinates = PriorCoordinates::kEcef;
  const LocalizedPriors bad = LocalizePriors(ecef, database, options);
  EXPECT_EQ(bad.priors.by_image.size(), 2u);
  EXPECT_TRUE(Mentions(bad.warnings, "not an earth-centred position"));
}

// COLMAP 3.10 on says what its priors are; a 3.8 database does not.
TEST(PosePriors, CoordinatesAsTheDatabaseStatesThem) {
  FeatureDatabase database;
  for (uint32_t id = 1; id <= 3; ++id) {
    database.images[id].image_id = id;
    database.images[id].prior_translation = Eigen::Vector3d(id, 2.0 * id, 0.5);
  }
  database.images[4].image_id = 4;  // no prior: says nothing
  database.images[4].prior_coordinate_system = PriorCoordinateSystem::kWgs84;
  EXPECT_EQ(DatabasePriorCoordinates(database, PriorCoordinates::kWgs84), PriorCoordinates::kWgs84);
  for (uint32_t id = 1; id <= 3; ++id) {
    database.images[id].prior_coordinate_system = PriorCoordinateSystem::kCartesian;
  }
  EXPECT_EQ(DatabasePriorCoordinates(database, PriorCoordinates::kWgs84), PriorCoordinates::kXyz);
  database.images[2].prior_coordinate_system = PriorCoordinateSystem::kWgs84;  // they disagree
  EXPECT_EQ(DatabasePriorCoordinates(database, PriorCoordinates::kEcef), PriorCoordinates::kEcef);
  for (uint32_t id = 1; id <= 3; ++id) {
    database.images[id].prior_coordinate_system = PriorCoordinateSystem::kWgs84;
  }
  EXPECT_EQ(DatabasePriorCoordinates(database, PriorCoordinates::kXyz), PriorCoordinates::kWgs84);
}

}  // namespace
}  // namespace ramap
