#include "ramap/io/exif.h"

#include <gtest/gtest.h>

#include <exiv2/exiv2.hpp>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

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

}  // namespace
}  // namespace ramap
