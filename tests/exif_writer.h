// Test helper: JPEGs with EXIF GPS tags, written with exiv2 as a camera would tag them.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace ramap::test {

// Writes `image` as a JPEG at `path` with GPSLatitude/Longitude (degrees, minutes, seconds to
// 1e-4 s, about 3 mm), their N/S and E/W references and GPSAltitude with its below-sea-level flag.
void WriteJpegWithGps(const std::string& path, const cv::Mat& image, double latitude,
                      double longitude, double altitude);

}  // namespace ramap::test
