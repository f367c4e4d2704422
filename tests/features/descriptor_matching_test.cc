// MatchDescriptors on hand-made descriptors whose distances can be read off: the nearest
// neighbour kept when it passes Lowe's ratio test and the cross check, Hamming distance for
// 32-byte descriptors, L2 otherwise, and the ratio of each match. (The matrix product against the
// distance loop: tests/features/matching_plan_test.cc.)
#include "ramap/features/descriptor_matching.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ramap {
namespace {

// 128-column descriptors, one row per entry: value `base` everywhere but `bumps` added at the
// given columns.
struct Row {
  uint8_t base;
  std::vector<std::pair<int, int>> bumps;  // column, amount
};

Descriptors Float(const std::vector<Row>& rows) {
  Descriptors descriptors;
  descriptors.num_cols = 128;
  for (const Row& row : rows) {
    std::vector<uint8_t> values(128, row.base);
    for (const auto& [column, amount] : row.bumps) values[column] += amount;
    descriptors.data.insert(descriptors.data.end(), values.begin(), values.end());
  }
  return descriptors;
}

// 32-byte descriptors whose first `bits[k]` bits are set.
Descriptors Binary(const std::vector<int>& bits) {
  Descriptors descriptors;
  descriptors.num_cols = 32;
  for (const int count : bits) {
    std::vector<uint8_t> values(32, 0);
    for (int b = 0; b < count; ++b) values[b / 8] |= static_cast<uint8_t>(1u << (b % 8));
    descriptors.data.insert(descriptors.data.end(), values.begin(), values.end());
  }
  return descriptors;
}

using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;

Pairs AsPairs(const std::vector<FeatureMatch>& matches) {
  Pairs pairs;
  for (const FeatureMatch& match : matches)
    pairs.emplace_back(match.point2D_idx1, match.point2D_idx2);
  return pairs;
}

TEST(DescriptorMatching, NearestNeighboursInL2WithTheirRatios) {
  // Image 1: rows at levels 10, 100, 200. Image 2: the same levels in another order, each moved by
  // 3 in one column (distance 3), and far from the others (distance >= 90 * sqrt(128)).
  const Descriptors one = Float({{10, {}}, {100, {}}, {200, {}}});
  const Descriptors two = Float({{200, {{5, 3}}}, {10, {{0, 3}}}, {100, {{127, 3}}}});
  for (const auto& match : {MatchDescriptors, MatchDescriptorsByLoop}) {
    std::vector<float> ratios;
    const std::vector<FeatureMatch> matches = match(one, two, {}, &ratios);
    EXPECT_EQ(AsPairs(matches), (Pairs{{0, 1}, {1, 2}, {2, 0}}));
    ASSERT_EQ(ratios.size(), 3u);
    // 3 against the second nearest: level 10 to 100 and 100 to 10 or 200 differ by 90 (and the
    // bump), 200 to 100 by 100.
    EXPECT_NEAR(ratios[0], 3.0 / std::sqrt(90.0 * 90 * 127 + 93.0 * 93), 1e-6);
    EXPECT_NEAR(ratios[2], 3.0 / std::sqrt(100.0 * 100 * 127 + 97.0 * 97), 1e-6);
  }
}

TEST(DescriptorMatching, AmbiguousNeighboursFailTheRatioTest) {
  // Row 0 of image 1 is 10 from row 0 and 11 from row 1 of image 2: ratio 0.91 > 0.8.
  const Descriptors one = Float({{50, {}}});
  const Descriptors two = Float({{50, {{0, 10}}}, {50, {{1, 11}}}});
  std::vector<float> ratios;
  EXPECT_TRUE(MatchDescriptors(one, two, {}, &ratios).empty());
  EXPECT_TRUE(ratios.empty());
  DescriptorMatchingOptions loose;
  loose.max_ratio = 0.95;
  EXPECT_EQ(AsPairs(MatchDescriptors(one, two, loose, &ratios)), (Pairs{{0, 0}}));
  ASSERT_EQ(ratios.size(), 1u);
  EXPECT_NEAR(ratios[0], 10.0 / 11.0, 1e-6);
}

TEST(DescriptorMatching, CrossCheckKeepsMutualNearestNeighboursOnly) {
  // Rows 0 and 1 of image 1 are both nearest to row 0 of image 2, which is nearest to row 1.
  const Descriptors one = Float({{60, {{0, 20}}}, {60, {{0, 2}}}});
  const Descriptors two = Float({{60, {}}, {150, {}}});
  EXPECT_EQ(AsPairs(MatchDescriptors(one, two, {})), (Pairs{{1, 0}}));
  DescriptorMatchingOptions no_check;
  no_check.cross_check = false;
  EXPECT_EQ(AsPairs(MatchDescriptors(one, two, no_check)), (Pairs{{0, 0}, {1, 0}}));
}

TEST(DescriptorMatching, ThirtyTwoByteDescriptorsByHammingDistance) {
  // Image 1: no bit set. Image 2: 3 bits, then 20, then 200: the nearest at 3, ratio 3 / 20.
  std::vector<float> ratios;
  const std::vector<FeatureMatch> matches =
      MatchDescriptors(Binary({0}), Binary({20, 3, 200}), {}, &ratios);
  EXPECT_EQ(AsPairs(matches), (Pairs{{0, 1}}));
  ASSERT_EQ(ratios.size(), 1u);
  EXPECT_FLOAT_EQ(ratios[0], 3.0f / 20.0f);
}

TEST(DescriptorMatching, NothingToCompareGivesNoMatches) {
  const Descriptors one = Float({{10, {}}, {100, {}}});
  EXPECT_TRUE(MatchDescriptors(one, Float({{10, {}}}), {}).empty());  // no second nearest
  EXPECT_TRUE(MatchDescriptors(Float({}), one, {}).empty());
  EXPECT_TRUE(MatchDescriptors(one, Binary({1, 2}), {}).empty());  // 128 against 32 columns
}

TEST(DescriptorMatching, EvenSubsetWithoutScalesAndAllWhenFewEnough) {
  Descriptors descriptors;
  descriptors.num_cols = 128;
  for (int k = 0; k < 10; ++k) descriptors.data.insert(descriptors.data.end(), 128, k);
  Keypoints plain;
  plain.num_cols = 2;
  plain.data.assign(20, 0.0f);
  // Rows k * 10 / 4: 0, 2, 5, 7.
  const Descriptors subset = LargestScaleDescriptors(plain, descriptors, 4);
  ASSERT_EQ(subset.size(), 4u);
  const std::vector<int> expected = {0, 2, 5, 7};
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(subset.data[k * 128], expected[k]);
  EXPECT_EQ(LargestScaleDescriptors(plain, descriptors, 10).data, descriptors.data);
  EXPECT_EQ(LargestScaleDescriptors(plain, descriptors, 50).data, descriptors.data);
}

}  // namespace
}  // namespace ramap
