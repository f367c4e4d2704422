#include "ramap/io/exif.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exiv2/exiv2.hpp>
#include <sstream>
#include <utility>

namespace ramap {
namespace {

std::optional<double> Number(const Exiv2::ExifData& exif, const char* key) {
  const auto it = exif.findKey(Exiv2::ExifKey(key));
  if (it == exif.end() || it->count() == 0) return std::nullopt;
  const double value = it->toFloat(0);
  if (!(value > 0) || !std::isfinite(value)) return std::nullopt;
  return value;
}

// Degrees from the three rationals (degrees, minutes, seconds) of a GPS coordinate, signed by its
// reference tag ("S" and "W" are negative).
std::optional<double> GpsDegrees(const Exiv2::ExifData& exif, const char* key, const char* ref_key,
                                 char negative_ref) {
  const auto it = exif.findKey(Exiv2::ExifKey(key));
  if (it == exif.end() || it->count() != 3) return std::nullopt;
  const double degrees = it->toFloat(0) + it->toFloat(1) / 60.0 + it->toFloat(2) / 3600.0;
  if (!std::isfinite(degrees)) return std::nullopt;
  const auto ref = exif.findKey(Exiv2::ExifKey(ref_key));
  const bool negative =
      ref != exif.end() && !ref->toString().empty() &&
      std::toupper(static_cast<unsigned char>(ref->toString()[0])) == negative_ref;
  return negative ? -degrees : degrees;
}

}  // namespace

std::optional<GeodeticPoint> ExifGpsPosition(const std::string& path) {
  try {
    auto image = Exiv2::ImageFactory::open(path);
    if (image.get() == nullptr) return std::nullopt;
    image->readMetadata();
    const Exiv2::ExifData& exif = image->exifData();
    const auto latitude =
        GpsDegrees(exif, "Exif.GPSInfo.GPSLatitude", "Exif.GPSInfo.GPSLatitudeRef", 'S');
    const auto longitude =
        GpsDegrees(exif, "Exif.GPSInfo.GPSLongitude", "Exif.GPSInfo.GPSLongitudeRef", 'W');
    if (!latitude || !longitude) return std::nullopt;
    GeodeticPoint point{*latitude, *longitude, 0.0};
    const auto altitude = exif.findKey(Exiv2::ExifKey("Exif.GPSInfo.GPSAltitude"));
    if (altitude != exif.end() && altitude->count() == 1 && std::isfinite(altitude->toFloat(0))) {
      point.altitude_m = altitude->toFloat(0);
      const auto ref = exif.findKey(Exiv2::ExifKey("Exif.GPSInfo.GPSAltitudeRef"));
      if (ref != exif.end() && ref->count() == 1 && ref->toLong(0) == 1) point.altitude_m *= -1;
    }
    if (!IsValidGeodeticPoint(point)) return std::nullopt;
    return point;
  } catch (const Exiv2::AnyError&) {
    return std::nullopt;
  }
}

namespace {

// The factor from the original image (EXIF's pixel dimensions) to the file, and whether the file
// is a crop of it. Without EXIF dimensions the file is taken as the original.
void ScaleToFile(const Exiv2::ExifData& exif, int width, int height, ExifFocalLength* focal) {
  const auto x = Number(exif, "Exif.Photo.PixelXDimension");
  const auto y = Number(exif, "Exif.Photo.PixelYDimension");
  if (!x || !y) return;
  focal->exif_width = static_cast<int>(*x);
  focal->exif_height = static_cast<int>(*y);
  // EXIF's dimensions are the sensor's; a decoder that applied the orientation tag turned them.
  double exif_w = *x, exif_h = *y;
  if ((exif_w > exif_h) != (width > height) && exif_w != exif_h) std::swap(exif_w, exif_h);
  const double sx = width / exif_w, sy = height / exif_h;
  // One pixel of rounding on either side of a resize.
  const double tolerance = 1.0 / std::min(width, height) + 1.0 / std::min(exif_w, exif_h);
  std::ostringstream note;
  if (std::abs(std::log(sx / sy)) > tolerance) {
    focal->cropped = true;
    focal->focal_px *= std::max(sx, sy);
    note << "cropped: the file is " << width << "x" << height << ", EXIF's image "
         << focal->exif_width << "x" << focal->exif_height
         << ", so the focal length is a start only (the crop assumed to cut one side)";
  } else if (std::abs(sx - 1.0) > tolerance) {
    focal->focal_px *= sx;
    note << "resized from EXIF's " << focal->exif_width << "x" << focal->exif_height << " by "
         << sx;
  }
  focal->note = note.str();
}

}  // namespace

std::optional<ExifFocalLength> ReadExifFocalLength(const std::string& path, int width, int height) {
  try {
    auto image = Exiv2::ImageFactory::open(path);
    if (image.get() == nullptr || width <= 0 || height <= 0) return std::nullopt;
    image->readMetadata();
    const Exiv2::ExifData& exif = image->exifData();
    if (exif.empty()) return std::nullopt;
    ExifFocalLength focal;
    if (const auto f35 = Number(exif, "Exif.Photo.FocalLengthIn35mmFilm")) {
      // A full frame is 36 mm wide: f35 / 36 of the original's longest side, which is the file's
      // longest side until ScaleToFile finds EXIF's dimensions.
      const auto x = Number(exif, "Exif.Photo.PixelXDimension");
      const auto y = Number(exif, "Exif.Photo.PixelYDimension");
      const double longest = x && y ? std::max(*x, *y) : std::max(width, height);
      focal.focal_px = *f35 / 36.0 * longest;
      focal.source = "35 mm equivalent";
    } else {
      const auto f_mm = Number(exif, "Exif.Photo.FocalLength");
      const auto x_resolution = Number(exif, "Exif.Photo.FocalPlaneXResolution");
      if (!f_mm || !x_resolution) return std::nullopt;
      // Resolution unit: 2 inch (default), 3 cm, 4 mm, 5 um.
      const double unit = Number(exif, "Exif.Photo.FocalPlaneResolutionUnit").value_or(2.0);
      const double mm_per_unit = unit == 3 ? 10.0 : unit == 4 ? 1.0 : unit == 5 ? 1e-3 : 25.4;
      focal.focal_px = *f_mm * (*x_resolution / mm_per_unit);
      focal.source = "focal plane";
    }
    ScaleToFile(exif, width, height, &focal);
    if (!(focal.focal_px > 0) || !std::isfinite(focal.focal_px)) return std::nullopt;
    return focal;
  } catch (const Exiv2::AnyError&) {
    return std::nullopt;
  }
}

}  // namespace ramap
