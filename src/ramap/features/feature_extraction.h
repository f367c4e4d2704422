// Keypoints and descriptors of one image with OpenCV, for image-list input: ORB (the paper's
// features; Rublee et al., ICCV 2011) or SIFT (Lowe, IJCV 2004), stored as COLMAP stores them.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

enum class FeatureType { kOrb, kSift };

// "orb" or "sift"; throws InputError naming --FeatureExtraction.type otherwise.
FeatureType FeatureTypeFromName(const std::string& name);
std::string FeatureTypeName(FeatureType type);

struct FeatureExtractionOptions {
  // SIFT by default: ORB (the paper's features) is faster to extract but less accurate on small
  // or weakly textured collections (BENCHMARKS.md, "From images", templeRing).
  FeatureType type = FeatureType::kSift;
  // Images larger than this (longest side, pixels) are downscaled for detection; keypoints are
  // scaled back to full resolution (COLMAP's SiftExtraction.max_image_size default is 3200; 1600
  // is what ../shared/data/README.md's COLMAP timings used).
  int max_image_size = 1600;
  // Keypoints kept at most (COLMAP's SiftExtraction.max_num_features default: 8192).
  int max_num_features = 8192;

  void Check() const;  // throws InputError naming the option
};

// Its options (--FeatureExtraction.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<FeatureExtractionOptions>& FeatureExtractionOptionTable();

struct ImageFeatures {
  Keypoints
      keypoints;  // 4 columns: x, y (COLMAP's convention, pixel centres at +0.5), scale, angle
  Descriptors descriptors;  // ORB: 32 bytes a row; SIFT: 128 bytes (OpenCV's floats, clamped)
};

// Features of a grey image (8 bit, one channel) at full resolution.
ImageFeatures ExtractFeatures(const cv::Mat& grey, const FeatureExtractionOptions& options);

}  // namespace ramap
