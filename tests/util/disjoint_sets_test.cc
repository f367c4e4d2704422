#include "ramap/util/disjoint_sets.h"

#include <gtest/gtest.h>

#include <random>

namespace ramap {
namespace {

// Roots() must agree with Find() on every element after unions in a random order, and every root
// must be the smallest element of its set.
TEST(DisjointSets, RootsInOnePassAgreeWithFind) {
  const uint32_t size = 2000;
  DisjointSets sets(size);
  std::mt19937 random(5);
  std::uniform_int_distribution<uint32_t> element(0, size - 1);
  for (int k = 0; k < 1500; ++k) sets.Union(element(random), element(random));
  const std::vector<uint32_t> roots = sets.Roots();
  ASSERT_EQ(roots.size(), size);
  size_t num_joined = 0;
  for (uint32_t x = 0; x < size; ++x) {
    EXPECT_EQ(roots[x], sets.Find(x));
    EXPECT_LE(roots[x], x);
    if (roots[x] != x) ++num_joined;
  }
  EXPECT_GT(num_joined, size / 2);  // the unions did join most elements
}

}  // namespace
}  // namespace ramap
