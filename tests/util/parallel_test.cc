#include "ramap/util/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace ramap {
namespace {

TEST(ParallelFor, RunsEveryItemOnce) {
  std::vector<std::atomic<int>> counts(1000);
  ParallelFor(counts.size(), 2, [&](size_t k) { ++counts[k]; });
  for (const std::atomic<int>& count : counts) EXPECT_EQ(count, 1);
}

TEST(ParallelFor, CarriesAWorkersExceptionToTheCaller) {
  for (const int threads : {1, 2, 4}) {
    std::atomic<int> started{0};
    std::ostringstream progress;
    // Item 7 fails whichever thread takes it; the caller sees that exception, not terminate().
    // The other items take 2 ms each, so that the rest of the loop (about 90 items) lasts far
    // longer than the failure takes to reach the other threads: instant items could all be taken
    // in the moment between item 7's throw and the loop's stop (seen once on 2 cores, 4 threads).
    EXPECT_THROW(ParallelFor(
                     100, threads,
                     [&](size_t k) {
                       ++started;
                       if (k == 7) throw std::out_of_range("item 7");
                       std::this_thread::sleep_for(std::chrono::milliseconds(2));
                     },
                     &progress, "work", "items"),
                 std::out_of_range)
        << threads << " threads";
    // The loop stops taking new items after the failure (those under way may finish).
    EXPECT_LT(started.load(), 100) << threads << " threads";
  }
}

TEST(NumShares, OnePerThreadButNoneTooSmall) {
  EXPECT_EQ(NumShares(10000, 2, 2000), 2u);
  EXPECT_EQ(NumShares(3999, 2, 2000), 1u);  // two would hold under 2000 each
  EXPECT_EQ(NumShares(10000, 8, 2000), 5u);
  EXPECT_EQ(NumShares(0, 2, 1), 1u);
  EXPECT_EQ(NumShares(100, 0, 1), 1u);
}

TEST(ForEachShare, CoversTheRangeOnceInContiguousSharesInOrder) {
  for (const size_t num_shares : {1u, 2u, 3u, 7u}) {
    std::vector<std::pair<size_t, size_t>> bounds(num_shares);
    std::vector<std::atomic<int>> counts(1001);
    ForEachShare(counts.size(), num_shares, [&](size_t share, size_t begin, size_t end) {
      bounds[share] = {begin, end};
      for (size_t k = begin; k < end; ++k) ++counts[k];
    });
    for (const auto& count : counts) EXPECT_EQ(count, 1);
    EXPECT_EQ(bounds.front().first, 0u);
    EXPECT_EQ(bounds.back().second, counts.size());
    for (size_t share = 1; share < num_shares; ++share)
      EXPECT_EQ(bounds[share].first, bounds[share - 1].second);
  }
}

}  // namespace
}  // namespace ramap
