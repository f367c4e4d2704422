#include "ramap/features/feature_extraction.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "ramap/geometry/rotation.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"

namespace ramap {

FeatureType FeatureTypeFromName(const std::string& name) {
  if (name == "orb") return FeatureType::kOrb;
  if (name == "sift") return FeatureType::kSift;
  throw InputError("--FeatureExtraction.type", "'" + name + "' is not orb or sift");
}

std::string FeatureTypeName(FeatureType type) { return type == FeatureType::kOrb ? "orb" : "sift"; }

void FeatureExtractionOptions::Check() const {
  CheckOptionValues(FeatureExtractionOptionTable(), *this);
}

ImageFeatures ExtractFeatures(const cv::Mat& grey, const FeatureExtractionOptions& options) {
  options.Check();
  const int longest = std::max(grey.cols, grey.rows);
  const double scale = longest > options.max_image_size
                           ? static_cast<double>(options.max_image_size) / longest
                           : 1.0;
  cv::Mat detect_on = grey;
  if (scale < 1.0) cv::resize(grey, detect_on, cv::Size(), scale, scale, cv::INTER_AREA);

  cv::Ptr<cv::Feature2D> detector;
  if (options.type == FeatureType::kOrb) {
    // Eight pyramid levels at 1.2 (OpenCV's defaults, the paper's ORB-SLAM settings).
    detector = cv::ORB::create(options.max_num_features);
  } else {
    detector = cv::SIFT::create(options.max_num_features);
  }
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  detector->detectAndCompute(detect_on, cv::noArray(), keypoints, descriptors);

  ImageFeatures features;
  features.keypoints.num_cols = 4;
  features.keypoints.data.reserve(keypoints.size() * 4);
  for (const cv::KeyPoint& k : keypoints) {
    // OpenCV puts pixel centres at integers, COLMAP at +0.5.
    features.keypoints.data.push_back(static_cast<float>((k.pt.x + 0.5) / scale));
    features.keypoints.data.push_back(static_cast<float>((k.pt.y + 0.5) / scale));
    features.keypoints.data.push_back(static_cast<float>(k.size / scale));
    features.keypoints.data.push_back(static_cast<float>(k.angle * kDegToRad));
  }
  features.descriptors.num_cols = descriptors.cols;
  if (descriptors.empty()) {
    features.descriptors.num_cols = options.type == FeatureType::kOrb ? 32 : 128;
  } else if (descriptors.type() == CV_8U) {
    features.descriptors.data.assign(descriptors.datastart, descriptors.dataend);
  } else {
    // SIFT: OpenCV's float descriptors hold values of at most 255 after its own scaling.
    features.descriptors.data.reserve(descriptors.total());
    for (int r = 0; r < descriptors.rows; ++r) {
      for (int c = 0; c < descriptors.cols; ++c) {
        const float v = descriptors.at<float>(r, c);
        features.descriptors.data.push_back(
            static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L)));
      }
    }
  }
  return features;
}

}  // namespace ramap
