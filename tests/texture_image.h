// A grey test image both feature detectors find many features in: uniform noise blurred into blobs.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace ramap::test {

inline cv::Mat BlurredNoise(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 2.0);
  cv::normalize(image, image, 0, 255, cv::NORM_MINMAX);
  return image;
}

}  // namespace ramap::test
