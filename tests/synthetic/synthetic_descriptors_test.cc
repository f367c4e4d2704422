// AddSyntheticDescriptors: one SIFT-shaped row per keypoint, views of one point alike and every
// other descriptor far from them, the same output for the same seed.
#include "ramap/synthetic/synthetic_descriptors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ramap {
namespace {

// A 6-frame line with wrong matches, so that some keypoints observe no 3D point.
SyntheticScene SmallScene() {
  SyntheticSceneOptions options;
  options.num_images = 6;
  options.num_points = 300;
  options.outlier_ratio = 0.2;
  options.seed = 5;
  return BuildSyntheticScene(options);
}

SyntheticScene WithDescriptors(const SyntheticDescriptorOptions& options) {
  SyntheticScene scene = SmallScene();
  AddSyntheticDescriptors(options, &scene);
  return scene;
}

double Distance(const Descriptors& a, size_t row_a, const Descriptors& b, size_t row_b) {
  double sum = 0;
  for (int k = 0; k < 128; ++k) {
    const double d = double{a.data[row_a * 128 + k]} - double{b.data[row_b * 128 + k]};
    sum += d * d;
  }
  return std::sqrt(sum);
}

TEST(SyntheticDescriptors, OneSiftShapedRowPerKeypoint) {
  const SyntheticScene scene = WithDescriptors(SyntheticDescriptorOptions());
  ASSERT_EQ(scene.database.descriptors.size(), scene.database.images.size());
  for (const auto& [image_id, keypoints] : scene.database.keypoints) {
    const Descriptors& descriptors = scene.database.descriptors.at(image_id);
    EXPECT_EQ(descriptors.num_cols, 128);
    ASSERT_EQ(descriptors.size(), keypoints.size()) << "image " << image_id;
    for (size_t row = 0; row < descriptors.size(); ++row) {
      double squared = 0;
      for (int k = 0; k < 128; ++k) squared += std::pow(descriptors.data[row * 128 + k], 2);
      // L2 norm 512 before rounding to bytes (and clamping at 255, which the spread values of a
      // 128-dimensional vector of norm 512 do not reach): rounding moves it by a few units.
      EXPECT_NEAR(std::sqrt(squared), 512.0, 6.0) << "image " << image_id << " row " << row;
    }
  }
}

TEST(SyntheticDescriptors, ViewsOfOnePointAreEachOthersNearestNeighbours) {
  const SyntheticScene scene = WithDescriptors(SyntheticDescriptorOptions());
  const Image& image1 = scene.ground_truth.images.at(1);
  const Image& image2 = scene.ground_truth.images.at(2);
  std::map<uint64_t, size_t> row_in_2;
  for (size_t row = 0; row < image2.points2D.size(); ++row) {
    if (image2.points2D[row].point3D_id != kInvalidPoint3DId) {
      row_in_2[image2.points2D[row].point3D_id] = row;
    }
  }
  const Descriptors& one = scene.database.descriptors.at(1);
  const Descriptors& two = scene.database.descriptors.at(2);
  int num_shared = 0;
  for (size_t row = 0; row < image1.points2D.size(); ++row) {
    const auto same = row_in_2.find(image1.points2D[row].point3D_id);
    if (same == row_in_2.end()) continue;
    ++num_shared;
    const double to_same = Distance(one, row, two, same->second);
    double to_nearest_other = std::numeric_limits<double>::infinity();
    for (size_t other = 0; other < two.size(); ++other) {
      if (other != same->second) {
        to_nearest_other = std::min(to_nearest_other, Distance(one, row, two, other));
      }
    }
    // Two views differ by noise of sigma 8 in each of 128 values, sqrt(2 * 128) * 8 = 128 apart;
    // unrelated descriptors are about 430 apart. The ratio test (0.8) passes every true match.
    EXPECT_LT(to_same, 0.8 * to_nearest_other) << "keypoint " << row;
  }
  EXPECT_GT(num_shared, 50);
}

TEST(SyntheticDescriptors, WithoutNoiseViewsOfOnePointAreIdentical) {
  SyntheticDescriptorOptions exact;
  exact.noise_sigma = 0.0;
  const SyntheticScene scene = WithDescriptors(exact);
  std::map<uint64_t, std::vector<uint8_t>> of_point;
  int num_compared = 0;
  for (const auto& [image_id, image] : scene.ground_truth.images) {
    const Descriptors& descriptors = scene.database.descriptors.at(image_id);
    for (size_t row = 0; row < image.points2D.size(); ++row) {
      const uint64_t point_id = image.points2D[row].point3D_id;
      if (point_id == kInvalidPoint3DId) continue;
      const std::vector<uint8_t> descriptor(descriptors.data.begin() + row * 128,
                                            descriptors.data.begin() + (row + 1) * 128);
      const auto [known, inserted] = of_point.emplace(point_id, descriptor);
      if (!inserted) {
        EXPECT_EQ(known->second, descriptor) << "point " << point_id;
        ++num_compared;
      }
    }
  }
  EXPECT_GT(num_compared, 100);
}

TEST(SyntheticDescriptors, TheSeedDecidesTheDescriptors) {
  const SyntheticScene a = WithDescriptors(SyntheticDescriptorOptions());
  const SyntheticScene b = WithDescriptors(SyntheticDescriptorOptions());
  SyntheticDescriptorOptions other;
  other.seed = 2;
  const SyntheticScene c = WithDescriptors(other);
  for (const auto& [image_id, descriptors] : a.database.descriptors) {
    EXPECT_EQ(descriptors.data, b.database.descriptors.at(image_id).data);
    EXPECT_NE(descriptors.data, c.database.descriptors.at(image_id).data);
  }
}

}  // namespace
}  // namespace ramap
