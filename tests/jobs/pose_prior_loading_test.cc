// LoadPosePriors: priors read from where --PosePrior.* says (the database, a file, or nowhere) in
// the stated or detected coordinates, the warnings logged ten at most, and the summary's block.
#include "ramap/jobs/pose_prior_loading.h"

#include <gtest/gtest.h>

#include <sstream>

#include "ramap/geometry/geodetic.h"
#include "ramap/io/pose_prior_file.h"
#include "test_support.h"

namespace ramap {
namespace {

const GeodeticPoint kOrigin{49.011, 8.4165, 115.0};

// Images image1.jpg ... imageN.jpg; the first `num_gps` with WGS84 fixes (as COLMAP 3.8 stores
// EXIF GPS: latitude, longitude, altitude in prior_tx/ty/tz) 10 m apart eastwards of kOrigin.
FeatureDatabase ImagesWithGps(int count, int num_gps) {
  FeatureDatabase database;
  const LocalEnuFrame frame(kOrigin);
  for (int k = 1; k <= count; ++k) {
    Image& image = database.images[k];
    image.image_id = k;
    image.name = "image" + std::to_string(k) + ".jpg";
    if (k > num_gps) continue;
    const GeodeticPoint p = frame.ToGeodetic(Eigen::Vector3d(10.0 * k, 0, 2));
    image.prior_translation = Eigen::Vector3d(p.latitude_deg, p.longitude_deg, p.altitude_m);
  }
  return database;
}

TEST(PosePriorLoading, DatabaseGpsBecomesEastNorthUpAboutTheGivenOrigin) {
  PosePriorSource source;
  source.origin = "49.011,8.4165,115";
  source.std_x_m = 2.0;
  std::ostringstream log;
  const LocalizedPriors loaded = LoadPosePriors(source, ImagesWithGps(6, 5), "ramap mapper", &log);
  ASSERT_TRUE(loaded.priors.origin.has_value());
  EXPECT_EQ(loaded.priors.origin->latitude_deg, 49.011);
  ASSERT_EQ(loaded.priors.by_image.size(), 5u);
  for (const auto& [id, prior] : loaded.priors.by_image) {
    // GeographicLib there and back: far below a millimetre.
    EXPECT_LT((prior.center - Eigen::Vector3d(10.0 * id, 0, 2)).norm(), 1e-6) << "image " << id;
    EXPECT_EQ(prior.std_dev_m, Eigen::Vector3d(2, 3, 6));
  }
  EXPECT_EQ(log.str(), "[ramap] pose priors: 5 of 5 usable (database, wgs84)\n");
}

TEST(PosePriorLoading, AFileOfMetricPriorsIsReadAsGiven) {
  test::TempDir dir;
  WritePriorFile({{"image2.jpg", {1.5, -2, 3}, Eigen::Vector3d(0.1, 0.2, 0.3), ""},
                  {"image4.jpg", {4, 5, 6}, std::nullopt, ""}},
                 dir / "priors.txt");
  PosePriorSource source;
  source.path = dir / "priors.txt";
  source.type = "xyz";
  std::ostringstream log;
  // The database's own GPS is not read when a file is given.
  const LocalizedPriors loaded = LoadPosePriors(source, ImagesWithGps(5, 5), "ramap mapper", &log);
  EXPECT_FALSE(loaded.priors.origin.has_value());  // a metric frame without geodetic meaning
  ASSERT_EQ(loaded.priors.by_image.size(), 2u);
  EXPECT_EQ(loaded.priors.by_image.at(2).center, Eigen::Vector3d(1.5, -2, 3));
  EXPECT_EQ(loaded.priors.by_image.at(2).std_dev_m, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(loaded.priors.by_image.at(4).center, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(loaded.priors.by_image.at(4).std_dev_m, Eigen::Vector3d(3, 3, 6));  // the source's
  EXPECT_NE(log.str().find("2 of 2 usable (" + source.path + ", xyz)"), std::string::npos)
      << log.str();
}

TEST(PosePriorLoading, NoSourceNoPriorsAndNothingLogged) {
  PosePriorSource source;
  source.from_database = false;
  std::ostringstream log;
  const LocalizedPriors loaded = LoadPosePriors(source, ImagesWithGps(5, 5), "ramap mapper", &log);
  EXPECT_TRUE(loaded.priors.by_image.empty());
  EXPECT_EQ(loaded.num_records, 0);
  EXPECT_EQ(log.str(), "");
}

TEST(PosePriorLoading, AutoFollowsWhatTheDatabaseSaysOfItsPriors) {
  // Cartesian priors (COLMAP 3.10 on says so) are read as metres, not as latitudes.
  FeatureDatabase database = ImagesWithGps(4, 0);
  for (auto& [id, image] : database.images) {
    image.prior_translation = Eigen::Vector3d(100.0 * id, 0, 0);
    image.prior_coordinate_system = PriorCoordinateSystem::kCartesian;
  }
  const LocalizedPriors loaded =
      LoadPosePriors(PosePriorSource(), database, "ramap mapper", nullptr);
  ASSERT_EQ(loaded.priors.by_image.size(), 4u);
  EXPECT_FALSE(loaded.priors.origin.has_value());
  EXPECT_EQ(loaded.priors.by_image.at(3).center, Eigen::Vector3d(300, 0, 0));
}

TEST(PosePriorLoading, TenWarningsAtMostThenACount) {
  // 15 records for images the database does not have.
  test::TempDir dir;
  std::vector<PriorRecord> records;
  for (int k = 1; k <= 15; ++k)
    records.push_back({"other" + std::to_string(k) + ".jpg", Eigen::Vector3d(k, 0, 0)});
  records.push_back({"image1.jpg", {0, 0, 0}});
  records.push_back({"image2.jpg", {1, 0, 0}});
  records.push_back({"image3.jpg", {0, 1, 0}});
  WritePriorFile(records, dir / "priors.txt");
  PosePriorSource source;
  source.path = dir / "priors.txt";
  source.type = "xyz";
  std::ostringstream log;
  const LocalizedPriors loaded = LoadPosePriors(source, ImagesWithGps(3, 0), "ramap mapper", &log);
  EXPECT_EQ(loaded.priors.by_image.size(), 3u);
  EXPECT_EQ(loaded.warnings.size(), 15u);
  const std::string text = log.str();
  size_t num_warnings = 0;
  for (size_t at = text.find("ramap mapper: warning: "); at != std::string::npos;
       at = text.find("ramap mapper: warning: ", at + 1)) {
    ++num_warnings;
  }
  EXPECT_EQ(num_warnings, 11u) << text;  // ten warnings and the count
  EXPECT_NE(text.find("ramap mapper: warning: ... and 5 more priors not used\n"), std::string::npos)
      << text;
}

TEST(PosePriorLoading, BadSourceValuesNameTheirOption) {
  const FeatureDatabase database = ImagesWithGps(3, 3);
  PosePriorSource origin;
  origin.origin = "49.0,8.4";
  test::ExpectInputError([&] { LoadPosePriors(origin, database, "ramap mapper", nullptr); },
                         {"--PosePrior.origin"});
  PosePriorSource type;
  type.type = "utm";
  test::ExpectInputError([&] { LoadPosePriors(type, database, "ramap mapper", nullptr); },
                         {"--PosePrior.type", "utm"});
}

TEST(PosePriorLoading, SummaryBlockHoldsTheSourceAndTheAlignmentSettings) {
  PosePriorSource source;
  source.path = "gps.txt";
  source.std_z_m = 9;
  PriorAlignmentOptions alignment;
  const nlohmann::json json = PosePriorOptionsToJson(source, alignment);
  EXPECT_EQ(json["path"], "gps.txt");
  EXPECT_EQ(json["type"], "auto");
  EXPECT_EQ(json["from_database"], true);
  EXPECT_EQ(json["std_m"], nlohmann::json({3.0, 3.0, 9.0}));
  EXPECT_EQ(json["max_distance_from_origin_m"], 100e3);
  EXPECT_EQ(json["align"], alignment.align);
  EXPECT_EQ(json["min_num_inliers"], alignment.min_num_inliers);
  EXPECT_EQ(json["max_alignment_error_m"], alignment.max_alignment_error_m);
}

}  // namespace
}  // namespace ramap
