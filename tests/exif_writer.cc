#include "exif_writer.h"

#include <cmath>
#include <exiv2/exiv2.hpp>
#include <opencv2/imgcodecs.hpp>

namespace ramap::test {
namespace {

Exiv2::URationalValue DegreesMinutesSeconds(double degrees) {
  degrees = std::abs(degrees);
  const int whole = static_cast<int>(degrees);
  const int minutes = static_cast<int>((degrees - whole) * 60);
  const double seconds = (degrees - whole - minutes / 60.0) * 3600;
  Exiv2::URationalValue value;
  value.value_ = {
      {whole, 1}, {minutes, 1}, {static_cast<uint32_t>(std::lround(seconds * 1e4)), 10000}};
  return value;
}

}  // namespace

void WriteJpegWithGps(const std::string& path, const cv::Mat& image, double latitude,
                      double longitude, double altitude) {
  cv::imwrite(path, image);
  auto file = Exiv2::ImageFactory::open(path);
  file->readMetadata();
  Exiv2::ExifData exif;
  exif["Exif.GPSInfo.GPSLatitudeRef"] = latitude < 0 ? "S" : "N";
  exif["Exif.GPSInfo.GPSLatitude"] = DegreesMinutesSeconds(latitude);
  exif["Exif.GPSInfo.GPSLongitudeRef"] = longitude < 0 ? "W" : "E";
  exif["Exif.GPSInfo.GPSLongitude"] = DegreesMinutesSeconds(longitude);
  exif["Exif.GPSInfo.GPSAltitudeRef"] = static_cast<uint8_t>(altitude < 0 ? 1 : 0);
  exif["Exif.GPSInfo.GPSAltitude"] =
      Exiv2::URational(static_cast<uint32_t>(std::lround(std::abs(altitude) * 100)), 100);
  file->setExifData(exif);
  file->writeMetadata();
}

}  // namespace ramap::test
