// The focal length an image's EXIF tags give, in pixels (exiv2), for cameras without known
// intrinsics, as COLMAP's ImageReader takes it.
#pragma once

#include <optional>
#include <string>

namespace ramap {

// From Exif.Photo.FocalLengthIn35mmFilm (f35 / 36 mm times the longest side), else from
// Exif.Photo.FocalLength with the focal-plane resolution (mm times pixels per mm). Empty when the
// file has no EXIF, neither tag, or values that make no sense (zero, negative). Never throws on a
// file exiv2 cannot read: that is an image without EXIF.
std::optional<double> ExifFocalLengthPx(const std::string& path, int width, int height);

}  // namespace ramap
