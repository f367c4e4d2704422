// Image files decoded and encoded by OpenCV's imgcodecs, loaded on first use from a plug-in
// (src/plugins/image_codecs.cc, libramap_image_codecs.so). Linked into ramap itself, imgcodecs
// brings over a hundred shared libraries (GDAL, Poppler, OpenEXR, codecs) whose loading and
// relocation at start cost every ramap command more than all its other libraries together, though
// the mapper and most commands read no image (docs/benchmark-history.md, "Where the seconds of
// bundle adjustment go").
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // the cv::IMREAD_* flags only: ramap does not link imgcodecs
#include <string>
#include <vector>

namespace ramap {

// cv::imread(path, flags) (cv::IMREAD_*); empty when the file cannot be read or decoded.
cv::Mat ReadImageFile(const std::string& path, int flags);

// cv::imencode(extension, image, bytes): false when OpenCV cannot encode it in that format.
bool EncodeImage(const std::string& extension, const cv::Mat& image, std::vector<uchar>* bytes);

}  // namespace ramap
