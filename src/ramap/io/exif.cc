#include "ramap/io/exif.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exiv2/exiv2.hpp>

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

std::optional<double> ExifFocalLengthPx(const std::string& path, int width, int height) {
  try {
    auto image = Exiv2::ImageFactory::open(path);
    if (image.get() == nullptr) return std::nullopt;
    image->readMetadata();
    const Exiv2::ExifData& exif = image->exifData();
    if (exif.empty()) return std::nullopt;
    const double longest = std::max(width, height);
    if (const auto f35 = Number(exif, "Exif.Photo.FocalLengthIn35mmFilm")) {
      return *f35 / 36.0 * longest;  // a full frame is 36 mm wide
    }
    const auto f_mm = Number(exif, "Exif.Photo.FocalLength");
    const auto x_resolution = Number(exif, "Exif.Photo.FocalPlaneXResolution");
    if (!f_mm || !x_resolution) return std::nullopt;
    // Resolution unit: 2 inch (default), 3 cm, 4 mm, 5 um.
    const double unit = Number(exif, "Exif.Photo.FocalPlaneResolutionUnit").value_or(2.0);
    const double mm_per_unit = unit == 3 ? 10.0 : unit == 4 ? 1.0 : unit == 5 ? 1e-3 : 25.4;
    return *f_mm * (*x_resolution / mm_per_unit);
  } catch (const Exiv2::AnyError&) {
    return std::nullopt;
  }
}

}  // namespace ramap
