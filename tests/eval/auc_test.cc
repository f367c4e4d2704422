#include "ramap/eval/auc.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ramap/util/error.h"

namespace ramap {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(EvalAuc, HandComputedBenchmarkCurve) {
  // Errors 0.5, 2, 4, 7 and one failure: n = 5, recall steps of 0.2. The benchmark curve joins
  // (0,0) (0.5,0.2) (2,0.4) (4,0.6) (7,0.8) by straight lines, then stays flat to T.
  // T=1:  0.5*0.2/2 + 0.5*0.2                               = 0.15 -> 0.15
  // T=3:  0.05 + 1.5*(0.2+0.4)/2 + 1*0.4                    = 0.9  -> 0.3
  // T=5:  0.05 + 0.45 + 2*(0.4+0.6)/2 + 1*0.6               = 2.1  -> 0.42
  // T=10: 0.05 + 0.45 + 1.0 + 3*(0.6+0.8)/2 + 3*0.8         = 6.0  -> 0.6
  const std::vector<double> aucs = ComputeAuc({4.0, kInf, 0.5, 7.0, 2.0}, {1, 3, 5, 10});
  ASSERT_EQ(aucs.size(), 4u);
  EXPECT_NEAR(aucs[0], 0.15, 1e-15);
  EXPECT_NEAR(aucs[1], 0.30, 1e-15);
  EXPECT_NEAR(aucs[2], 0.42, 1e-15);
  EXPECT_NEAR(aucs[3], 0.60, 1e-15);
}

TEST(EvalAuc, HandComputedStepIntegral) {
  // The exact integral of the step recall: the step is 0 on [0,0.5), 0.2 on [0.5,2), ...
  // T=1:  0.5*0.2                         = 0.1  -> 0.1
  // T=10: 1.5*0.2 + 2*0.4 + 3*0.6 + 3*0.8 = 5.3  -> 0.53
  const std::vector<double> aucs =
      ComputeAuc({4.0, kInf, 0.5, 7.0, 2.0}, {1, 10}, AucDefinition::kStepIntegral);
  EXPECT_NEAR(aucs[0], 0.10, 1e-15);
  EXPECT_NEAR(aucs[1], 0.53, 1e-15);
}

TEST(EvalAuc, EdgeCases) {
  EXPECT_EQ(ComputeAuc({0, 0, 0}, {1, 5}), std::vector<double>({1.0, 1.0}));
  EXPECT_EQ(ComputeAuc({}, {1}), std::vector<double>({0.0}));
  EXPECT_EQ(ComputeAuc({kInf, std::nan("")}, {1}), std::vector<double>({0.0}));
  // An error equal to the threshold counts as recalled (recall is #{e <= T}); one error at T
  // out of one: the line (0,0)-(T,1) has area T/2.
  EXPECT_NEAR(ComputeAuc({2.0}, {2.0})[0], 0.5, 1e-15);
  EXPECT_NEAR(ComputeAuc({2.0}, {2.0}, AucDefinition::kStepIntegral)[0], 0.0, 1e-15);
  // Ties: two errors at 1, T=2: (0,0)-(1,0.5) vertical to (1,1), flat: 0.25 + 1 -> 0.625.
  EXPECT_NEAR(ComputeAuc({1.0, 1.0}, {2.0})[0], 0.625, 1e-15);
  EXPECT_THROW(ComputeAuc({1.0}, {0.0}), InputError);
}

TEST(EvalAuc, FailuresScaleAucByRegisteredFraction) {
  const std::vector<double> good = {0.1, 0.7, 1.3, 2.9, 4.4, 8.0, 12.0};
  std::vector<double> with_failures = good;
  with_failures.insert(with_failures.end(), 3, kInf);
  const std::vector<double> thresholds = {1, 3, 5, 10};
  const std::vector<double> a = ComputeAuc(good, thresholds);
  const std::vector<double> b = ComputeAuc(with_failures, thresholds);
  for (size_t k = 0; k < thresholds.size(); ++k) EXPECT_NEAR(b[k], a[k] * 7.0 / 10.0, 1e-15);
}

}  // namespace
}  // namespace ramap
