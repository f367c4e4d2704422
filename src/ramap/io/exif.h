// What an image's EXIF tags say about its camera (exiv2): the focal length in pixels, for cameras
// without known intrinsics, and the GPS position, as COLMAP's ImageReader takes them.
#pragma once

#include <optional>
#include <string>

#include "ramap/geometry/geodetic.h"

namespace ramap {

// What an image's EXIF tags say its focal length is, in the pixels of the file as decoded.
struct ExifFocalLength {
  double focal_px = 0.0;
  // The tags it came from: "35 mm equivalent" (Exif.Photo.FocalLengthIn35mmFilm) or "focal plane"
  // (Exif.Photo.FocalLength with Exif.Photo.FocalPlaneXResolution and its unit).
  std::string source;
  // Exif.Photo.PixelXDimension and PixelYDimension, the image the camera wrote (0: absent).
  int exif_width = 0;
  int exif_height = 0;
  // The file's aspect ratio differs from EXIF's pixel dimensions': the image was cropped after
  // the camera wrote it, so no tag gives its focal length. focal_px is then the value for a crop
  // that removed one side only (the other scaled like a resize): a start, not a calibration.
  bool cropped = false;
  // What was done, for the user: the resize factor, or why the value is a start only.
  std::string note;
};

// The focal length of the image at `path`, `width` x `height` pixels as decoded (a decoder that
// applied the EXIF orientation swaps them: both orientations are accepted). From the 35 mm
// equivalent, f35 / 36 mm times the original frame's longest side; else from the focal length in
// mm times the focal-plane resolution. Either is the original image's, so it is scaled to the file
// by EXIF's pixel dimensions when they are there (a resized photo; COLMAP scales alike), and
// flagged `cropped` when the aspect ratios disagree. A crop of the same aspect ratio, or a file
// without pixel dimensions, cannot be told from the original: the mapper tests every EXIF value
// against the pairs (estimators/view_graph_calibration.h). Empty when the file has no EXIF,
// neither tag, or values that make no sense (zero, negative). Never throws on a file exiv2 cannot
// read: that is an image without EXIF.
std::optional<ExifFocalLength> ReadExifFocalLength(const std::string& path, int width, int height);

// Exif.GPSInfo latitude and longitude (degrees, minutes, seconds with their N/S, E/W references)
// and altitude (with its above/below reference; 0 when the tag is missing). EXIF altitudes are
// above sea level, not the ellipsoid: the tens of metres between the two are left to the robust
// alignment and the vertical standard deviation, as COLMAP does. Empty without both coordinates
// or with values out of range; never throws on a file exiv2 cannot read.
std::optional<GeodeticPoint> ExifGpsPosition(const std::string& path);

}  // namespace ramap
