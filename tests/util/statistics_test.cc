// Median and MedianPoint: the upper median, coordinate by coordinate, and the error on no values.
#include "ramap/util/statistics.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace ramap {
namespace {

TEST(Statistics, MedianOfAnOddCountIsTheMiddleValue) {
  EXPECT_EQ(Median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(Median({7.0}), 7.0);
}

TEST(Statistics, MedianOfAnEvenCountIsTheUpperOfTheTwoMiddleValues) {
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 2.0}), 3.0);  // sorted 1 2 3 4: element 4 / 2 = 2
  EXPECT_EQ(Median({-1.0, -2.0}), -1.0);
}

TEST(Statistics, MedianPointTakesEachCoordinateOnItsOwn) {
  // No input point is the median: each axis has its own middle value.
  const std::vector<Eigen::Vector3d> points = {
      {0.0, 10.0, -5.0}, {1.0, 30.0, -7.0}, {2.0, 20.0, -6.0}};
  EXPECT_EQ(MedianPoint(points), Eigen::Vector3d(1.0, 20.0, -6.0));
}

TEST(Statistics, NoValuesIsAnError) {
  EXPECT_THROW(Median({}), std::invalid_argument);
  EXPECT_THROW(MedianPoint({}), std::invalid_argument);
}

}  // namespace
}  // namespace ramap
