#include "ramap/io/exif.h"

#include <gtest/gtest.h>

#include <cmath>
#include <exiv2/exiv2.hpp>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "exif_writer.h"
#include "ramap/features/image_reader.h"
#include "test_support.h"

namespace ramap {
namespace {

void WriteJpegWithExif(const std::string& path, const std::string& key, double value) {
  cv::imwrite(path, cv::Mat(300, 400, CV_8UC3, cv::Scalar(10, 200, 30)));
  auto image = Exiv2::ImageFactory::open(path);
  image->readMetadata();
  Exiv2::ExifData exif;
  if (key == "Exif.Photo.FocalLengthIn35mmFilm") {
    exif[key] = static_cast<uint16_t>(value);
  } else {
    exif["Exif.Photo.FocalLength"] = Exiv2::URational(static_cast<int>(value * 10), 10);
    // 100 pixels per mm on the focal plane.
    exif["Exif.Photo.FocalPlaneXResolution"] = Exiv2::URational(100, 1);
    exif["Exif.Photo.FocalPlaneResolutionUnit"] = static_cast<uint16_t>(4);
  }
  image->setExifData(exif);
  image->writeMetadata();
}

TEST(Exif, FocalLengthFromTheTagsOfAJpegTheTestWrote) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "f35.jpg", "Exif.Photo.FocalLengthIn35mmFilm", 36);
  EXPECT_NEAR(ExifFocalLengthPx(dir / "f35.jpg", 400, 300).value_or(-1), 400.0, 1e-9);
  WriteJpegWithExif(dir / "mm.jpg", "Exif.Photo.FocalLength", 4.5);
  EXPECT_NEAR(ExifFocalLengthPx(dir / "mm.jpg", 400, 300).value_or(-1), 450.0, 1e-9);
  cv::imwrite(dir / "plain.jpg", cv::Mat(30, 40, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_FALSE(ExifFocalLengthPx(dir / "plain.jpg", 40, 30).has_value());
  std::ofstream(dir / "broken.jpg") << "no jpeg";
  EXPECT_FALSE(ExifFocalLengthPx(dir / "broken.jpg", 40, 30).has_value());
}

TEST(Exif, ImageReaderTakesTheExifFocalLength) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "f35.jpg", "Exif.Photo.FocalLengthIn35mmFilm", 72);
  ExtractionSummary summary;
  const FeatureDatabase database = ExtractImageFeatures(
      dir.path(), {"f35.jpg"}, ImageReaderOptions(), FeatureExtractionOptions(), &summary);
  ASSERT_EQ(database.cameras.size(), 1u);
  EXPECT_NEAR(database.cameras.at(1).params[0], 800.0, 1e-9);  // 72 / 36 * 400
  EXPECT_TRUE(database.cameras.at(1).has_prior_focal_length);
}

void WriteJpegWithGps(const std::string& path, double latitude, double longitude, double altitude) {
  test::WriteJpegWithGps(path, cv::Mat(300, 400, CV_8UC3, cv::Scalar(10, 200, 30)), latitude,
                         longitude, altitude);
}

TEST(Exif, GpsPositionFromTheTagsOfAJpegTheTestWrote) {
  test::TempDir dir;
  WriteJpegWithGps(dir / "karlsruhe.jpg", 49.0113456, 8.4165432, 115.25);
  const std::optional<GeodeticPoint> north_east = ExifGpsPosition(dir / "karlsruhe.jpg");
  ASSERT_TRUE(north_east.has_value());
  // 1e-4 arc seconds is 3 mm.
  EXPECT_NEAR(north_east->latitude_deg, 49.0113456, 1e-7);
  EXPECT_NEAR(north_east->longitude_deg, 8.4165432, 1e-7);
  EXPECT_NEAR(north_east->altitude_m, 115.25, 1e-9);
  WriteJpegWithGps(dir / "dead_sea.jpg", -33.8688, -70.5, -420.5);  // south, west, below sea
  const std::optional<GeodeticPoint> south_west = ExifGpsPosition(dir / "dead_sea.jpg");
  ASSERT_TRUE(south_west.has_value());
  EXPECT_NEAR(south_west->latitude_deg, -33.8688, 1e-7);
  EXPECT_NEAR(south_west->longitude_deg, -70.5, 1e-7);
  EXPECT_NEAR(south_west->altitude_m, -420.5, 1e-9);
  cv::imwrite(dir / "plain.jpg", cv::Mat(30, 40, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_FALSE(ExifGpsPosition(dir / "plain.jpg").has_value());
  std::ofstream(dir / "broken.jpg") << "no jpeg";
  EXPECT_FALSE(ExifGpsPosition(dir / "broken.jpg").has_value());

  // The image reader stores it as COLMAP does: latitude, longitude, altitude in prior_t.
  ExtractionSummary summary;
  const FeatureDatabase database =
      ExtractImageFeatures(dir.path(), {"karlsruhe.jpg", "plain.jpg"}, ImageReaderOptions(),
                           FeatureExtractionOptions(), &summary);
  EXPECT_EQ(summary.num_images_with_gps, 1);
  ASSERT_TRUE(database.images.at(1).prior_translation.has_value());
  EXPECT_NEAR(database.images.at(1).prior_translation->x(), 49.0113456, 1e-7);
  EXPECT_FALSE(database.images.at(2).prior_translation.has_value());
}

}  // namespace
}  // namespace ramap
