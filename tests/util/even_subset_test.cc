#include "ramap/util/even_subset.h"

#include <gtest/gtest.h>

#include <numeric>

namespace ramap {
namespace {

TEST(EvenSubset, KeepsShortListsWhole) {
  const std::vector<int> items = {4, 8, 15};
  EXPECT_EQ(EvenSubset(items, 3), items);
  EXPECT_EQ(EvenSubset(items, 10), items);
  EXPECT_EQ(EvenSubset(items, 0), items);  // 0: no limit
}

TEST(EvenSubset, SpreadsTheKeptItemsOverTheWholeList) {
  std::vector<int> items(641);
  std::iota(items.begin(), items.end(), 0);
  const std::vector<int> subset = EvenSubset(items, 256);
  ASSERT_EQ(subset.size(), 256u);
  EXPECT_EQ(subset.front(), 0);
  EXPECT_GE(subset.back(), 638);  // reaches the end, not only the first 256
  for (size_t k = 1; k < subset.size(); ++k) {
    const int gap = subset[k] - subset[k - 1];
    EXPECT_TRUE(gap == 2 || gap == 3) << "gap " << gap << " at " << k;
  }
}

}  // namespace
}  // namespace ramap
