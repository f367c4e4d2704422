// Area under the recall-vs-error curve (AUC), the pose-accuracy score of the COLMAP / GLOMAP
// reconstruction benchmarks (COLMAP's benchmark/reconstruction, after SuperGlue's pose_auc;
// Sarlin et al., CVPR 2020; Pan et al., "Global Structure-from-Motion Revisited", ECCV 2024).
#pragma once

#include <vector>

namespace ramap {

enum class AucDefinition {
  // What the benchmark scripts compute: the errors sorted, e_1 <= ... <= e_n (failures are +inf and
  // count in n), the points (0, 0), (e_k, k / n) joined by straight lines (trapezoid rule) up to
  // the last e_k <= T, then recall held flat to T; the area divided by T. In closed form, with m
  // errors <= T: (sum_{k<=m} (T - e_k) + e_m / 2) / (n T).
  kBenchmarkTrapezoid,
  // The exact integral of the step function recall(e) = #{e_k <= e} / n over [0, T], divided by
  // T: sum_{k<=m} (T - e_k) / (n T). Lower than the benchmark value by e_m / (2 n T).
  kStepIntegral,
};

// One AUC in [0, 1] per threshold (not percent). NaN errors count as failures (+inf). Thresholds
// must be > 0; an empty error list gives 0.
std::vector<double> ComputeAuc(const std::vector<double>& errors,
                               const std::vector<double>& thresholds,
                               AucDefinition definition = AucDefinition::kBenchmarkTrapezoid);

}  // namespace ramap
