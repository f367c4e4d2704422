#include "ramap/io/exif.h"

#include <algorithm>
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

}  // namespace

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
