// What an image's EXIF tags say about its camera (exiv2): the focal length in pixels, for cameras
// without known intrinsics, and the GPS position, as COLMAP's ImageReader takes them.
#pragma once

#include <optional>
#include <string>

#include "ramap/geometry/geodetic.h"

namespace ramap {

// From Exif.Photo.FocalLengthIn35mmFilm (f35 / 36 mm times the longest side), else from
// Exif.Photo.FocalLength with the focal-plane resolution (mm times pixels per mm). Empty when the
// file has no EXIF, neither tag, or values that make no sense (zero, negative). Never throws on a
// file exiv2 cannot read: that is an image without EXIF.
std::optional<double> ExifFocalLengthPx(const std::string& path, int width, int height);

// Exif.GPSInfo latitude and longitude (degrees, minutes, seconds with their N/S, E/W references)
// and altitude (with its above/below reference; 0 when the tag is missing). EXIF altitudes are
// above sea level, not the ellipsoid: the tens of metres between the two are left to the robust
// alignment and the vertical standard deviation, as COLMAP does. Empty without both coordinates
// or with values out of range; never throws on a file exiv2 cannot read.
std::optional<GeodeticPoint> ExifGpsPosition(const std::string& path);

}  // namespace ramap
