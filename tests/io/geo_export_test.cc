// The georeference written beside a model: its origin read back to the digit it was written with,
// one GeoJSON point per camera centre (longitude, latitude, altitude) with its name, and malformed
// origin files named.
#include "ramap/io/geo_export.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace ramap {
namespace {

const GeodeticPoint kKarlsruhe{49.011223456789, 8.423456789012, 115.25};

TEST(GeoExport, OriginReadsBackAsWritten) {
  test::TempDir dir;
  WriteGeoOrigin(kKarlsruhe, dir / "geo_origin.txt");
  const GeodeticPoint read = ReadGeoOrigin(dir / "geo_origin.txt");
  // Twelve significant digits: 1e-10 of a degree is 0.01 mm.
  EXPECT_NEAR(read.latitude_deg, kKarlsruhe.latitude_deg, 1e-10);
  EXPECT_NEAR(read.longitude_deg, kKarlsruhe.longitude_deg, 1e-10);
  EXPECT_NEAR(read.altitude_m, kKarlsruhe.altitude_m, 1e-9);
}

TEST(GeoExport, MalformedOriginFilesAreNamed) {
  test::TempDir dir;
  test::ExpectInputError([&] { ReadGeoOrigin(dir / "absent.txt"); }, {"absent.txt", "cannot open"});
  std::ofstream(dir / "comments.txt") << "# only a comment\n\n";
  test::ExpectInputError([&] { ReadGeoOrigin(dir / "comments.txt"); },
                         {"comments.txt", "no origin line"});
  std::ofstream(dir / "two.txt") << "49.0 8.4\n";
  test::ExpectInputError([&] { ReadGeoOrigin(dir / "two.txt"); },
                         {"two.txt", "LATITUDE LONGITUDE ALTITUDE", "'49.0 8.4'"});
  std::ofstream(dir / "four.txt") << "49.0 8.4 100 7\n";
  test::ExpectInputError([&] { ReadGeoOrigin(dir / "four.txt"); },
                         {"four.txt", "'49.0 8.4 100 7'"});
  std::ofstream(dir / "range.txt") << "# a latitude past the pole\n95.0 8.4 100\n";
  test::ExpectInputError([&] { ReadGeoOrigin(dir / "range.txt"); },
                         {"range.txt", "'95.0 8.4 100'"});
}

// Two cameras 100 m east and 50 m north of the origin, 10 m up.
Reconstruction TwoCameras() {
  Reconstruction model;
  model.cameras[1] = test::VgaPinholeCamera();
  const std::vector<std::pair<std::string, Eigen::Vector3d>> centres = {{"east.jpg", {100, 0, 10}},
                                                                        {"north.jpg", {0, 50, 10}}};
  uint32_t id = 1;
  for (const auto& [name, centre] : centres) {
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = name;
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.3 * id, Eigen::Vector3d::UnitX()));
    image.cam_from_world = Rigid3d(rotation, -(rotation * centre));
    model.images[id++] = image;
  }
  return model;
}

TEST(GeoExport, CamerasAreGeoJsonPointsAtTheirCentres) {
  test::TempDir dir;
  const Reconstruction model = TwoCameras();
  WriteGeoreference(model, kKarlsruhe, dir.path());
  const GeodeticPoint origin = ReadGeoOrigin(dir / "geo_origin.txt");
  EXPECT_NEAR(origin.latitude_deg, kKarlsruhe.latitude_deg, 1e-10);

  const nlohmann::json geojson = test::ReadJsonFile(dir / "cameras.geojson");
  EXPECT_EQ(geojson["type"], "FeatureCollection");
  ASSERT_EQ(geojson["features"].size(), 2u);
  const LocalEnuFrame frame(kKarlsruhe);
  const std::vector<std::pair<std::string, Eigen::Vector3d>> expected = {
      {"east.jpg", {100, 0, 10}}, {"north.jpg", {0, 50, 10}}};
  for (size_t k = 0; k < 2; ++k) {
    const nlohmann::json& feature = geojson["features"][k];
    EXPECT_EQ(feature["type"], "Feature");
    EXPECT_EQ(feature["properties"]["name"], expected[k].first);
    EXPECT_EQ(feature["properties"]["image_id"], k + 1);
    EXPECT_EQ(feature["geometry"]["type"], "Point");
    const nlohmann::json& coordinates = feature["geometry"]["coordinates"];
    ASSERT_EQ(coordinates.size(), 3u);
    // RFC 7946 order: longitude, latitude, altitude. Back into the ENU frame, the centre within
    // the 15 digits written (1e-9 degrees is 0.1 mm).
    const GeodeticPoint point{coordinates[1].get<double>(), coordinates[0].get<double>(),
                              coordinates[2].get<double>()};
    EXPECT_LT((frame.FromGeodetic(point) - expected[k].second).norm(), 1e-3);
  }
  // East is a larger longitude, north a larger latitude.
  EXPECT_GT(geojson["features"][0]["geometry"]["coordinates"][0].get<double>(),
            kKarlsruhe.longitude_deg);
  EXPECT_GT(geojson["features"][1]["geometry"]["coordinates"][1].get<double>(),
            kKarlsruhe.latitude_deg);
}

}  // namespace
}  // namespace ramap
