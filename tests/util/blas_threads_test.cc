#include "ramap/util/blas_threads.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

namespace ramap {
namespace {

TEST(BlasThreads, LimitsOpenBlasWhenItIsTheBlas) {
  using GetThreads = int (*)();
  const auto get_threads =
      reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (get_threads == nullptr) {
    EXPECT_FALSE(LimitBlasThreads(1));
    GTEST_SKIP() << "libblas.so.3 is not OpenBLAS here (scripts/install-deps.sh installs it)";
  }
  ASSERT_TRUE(LimitBlasThreads(1));
  EXPECT_EQ(get_threads(), 1);
  ASSERT_TRUE(LimitBlasThreads(0));  // at least one thread
  EXPECT_EQ(get_threads(), 1);
  ASSERT_TRUE(LimitBlasThreads(2));  // two, or fewer on a one-core machine
  EXPECT_GE(get_threads(), 1);
  EXPECT_LE(get_threads(), 2);
}

TEST(BlasThreads, OneThreadForAScopeThenThePreviousLimit) {
  if (BlasThreads() == 0) GTEST_SKIP() << "libblas.so.3 is not OpenBLAS here";
  ASSERT_TRUE(LimitBlasThreads(2));
  const int before = BlasThreads();  // 2, or 1 on a one-core machine
  {
    SingleBlasThread single;
    EXPECT_EQ(BlasThreads(), 1);
  }
  EXPECT_EQ(BlasThreads(), before);
}

}  // namespace
}  // namespace ramap
