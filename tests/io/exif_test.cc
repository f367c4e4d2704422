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

// A 400x300 JPEG with the focal length tag `key` at `value` and, when `original_width` is
// given, the original image's size in Exif.Photo.PixelXDimension and PixelYDimension (as a
// camera writes it before an editor resizes or crops the photo).
void WriteJpegWithExif(const std::string& path, const std::string& key, double value,
                       int original_width = 0, int original_height = 0) {
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
  if (original_width > 0) {
    exif["Exif.Photo.PixelXDimension"] = static_cast<uint32_t>(original_width);
    exif["Exif.Photo.PixelYDimension"] = static_cast<uint32_t>(original_height);
  }
  image->setExifData(exif);
  image->writeMetadata();
}

double ExifFocalPx(const std::string& path, int width, int height) {
  const std::optional<ExifFocalLength> focal = ReadExifFocalLength(path, width, height);
  return focal ? focal->focal_px : -1.0;
}

TEST(Exif, FocalLengthFromTheTagsOfAJpegTheTestWrote) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "f35.jpg", "Exif.Photo.FocalLengthIn35mmFilm", 36);
  EXPECT_NEAR(ExifFocalPx(dir / "f35.jpg", 400, 300), 400.0, 1e-9);
  WriteJpegWithExif(dir / "mm.jpg", "Exif.Photo.FocalLength", 4.5);
  EXPECT_NEAR(ExifFocalPx(dir / "mm.jpg", 400, 300), 450.0, 1e-9);
  cv::imwrite(dir / "plain.jpg", cv::Mat(30, 40, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_FALSE(ReadExifFocalLength(dir / "plain.jpg", 40, 30).has_value());
  std::ofstream(dir / "broken.jpg") << "no jpeg";
  EXPECT_FALSE(ReadExifFocalLength(dir / "broken.jpg", 40, 30).has_value());
}

// The focal length the image reader gives the camera of the one image `name` in `dir`.
Camera ReaderCamera(const test::TempDir& dir, const std::string& name) {
  ExtractionSummary summary;
  const FeatureDatabase database = ExtractImageFeatures(dir.path(), {name}, ImageReaderOptions(),
                                                        FeatureExtractionOptions(), &summary);
  EXPECT_EQ(database.cameras.size(), 1u);
  return database.cameras.begin()->second;
}

TEST(Exif, ImageReaderTakesTheExifFocalLength) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "f35.jpg", "Exif.Photo.FocalLengthIn35mmFilm", 72);
  const Camera camera = ReaderCamera(dir, "f35.jpg");
  EXPECT_NEAR(camera.params[0], 800.0, 1e-9);  // 72 / 36 * 400
  EXPECT_TRUE(camera.has_prior_focal_length);
}

// A photo taken at 1600x1200 and resized to 400x300: the focal-plane resolution is the sensor's,
// so the focal length in the file's pixels is a quarter of f_mm x resolution (4.5 mm at 100 px/mm:
// 450 px on the sensor, 112.5 px in the file). Read unscaled, it would be 4x too long.
TEST(Exif, FocalLengthOfAResizedImageIsInTheFilesPixels) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "resized.jpg", "Exif.Photo.FocalLength", 4.5, 1600, 1200);
  const Camera camera = ReaderCamera(dir, "resized.jpg");
  EXPECT_NEAR(camera.params[0], 112.5, 1e-6);
  EXPECT_TRUE(camera.has_prior_focal_length);
  // The 35 mm equivalent scales with the image alike: 72 / 36 of the longest side.
  WriteJpegWithExif(dir / "resized35.jpg", "Exif.Photo.FocalLengthIn35mmFilm", 72, 1600, 1200);
  EXPECT_NEAR(ReaderCamera(dir, "resized35.jpg").params[0], 800.0, 1e-6);
  // A decoder that applied the orientation tag turned the image: EXIF's 1200x1600 is the same.
  WriteJpegWithExif(dir / "turned.jpg", "Exif.Photo.FocalLength", 4.5, 1200, 1600);
  EXPECT_NEAR(ReaderCamera(dir, "turned.jpg").params[0], 112.5, 1e-6);
}

// A 4000x2000 photo cropped to 4:3 and resized to 400x300: no tag gives the file's focal length.
// The reader says so and gives the camera a start (the crop assumed to cut the long side only:
// 450 px x 300 / 2000), marked unknown so that the mapper estimates it.
TEST(Exif, ExifOfACroppedImageIsDetectedAsWrong) {
  test::TempDir dir;
  WriteJpegWithExif(dir / "cropped.jpg", "Exif.Photo.FocalLength", 4.5, 4000, 2000);
  const std::optional<ExifFocalLength> exif = ReadExifFocalLength(dir / "cropped.jpg", 400, 300);
  ASSERT_TRUE(exif.has_value());
  EXPECT_TRUE(exif->cropped);
  EXPECT_NE(exif->note.find("cropped"), std::string::npos) << exif->note;
  const Camera camera = ReaderCamera(dir, "cropped.jpg");
  EXPECT_FALSE(camera.has_prior_focal_length);
  EXPECT_NEAR(camera.params[0], 67.5, 1e-6);
  // The resized photo of the test above is not a crop.
  WriteJpegWithExif(dir / "resized.jpg", "Exif.Photo.FocalLength", 4.5, 1600, 1200);
  EXPECT_FALSE(ReadExifFocalLength(dir / "resized.jpg", 400, 300)->cropped);
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
