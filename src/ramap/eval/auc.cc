#include "ramap/eval/auc.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ramap/util/error.h"

namespace ramap {

std::vector<double> ComputeAuc(const std::vector<double>& errors,
                               const std::vector<double>& thresholds, AucDefinition definition) {
  std::vector<double> sorted = errors;
  for (double& e : sorted) {
    if (std::isnan(e)) e = std::numeric_limits<double>::infinity();
  }
  std::sort(sorted.begin(), sorted.end());
  const double n = static_cast<double>(sorted.size());
  std::vector<double> aucs;
  aucs.reserve(thresholds.size());
  for (double t : thresholds) {
    if (!(t > 0.0) || !std::isfinite(t)) {
      throw InputError("AUC thresholds", "each threshold must be finite and > 0");
    }
    if (sorted.empty()) {
      aucs.push_back(0.0);
      continue;
    }
    // Closed forms of the two integrals (see auc.h), summed in sorted order.
    double area = 0.0;
    double last = 0.0;
    bool any = false;
    for (double e : sorted) {
      if (!(e <= t)) break;
      area += t - e;
      last = e;
      any = true;
    }
    if (any && definition == AucDefinition::kBenchmarkTrapezoid) area += 0.5 * last;
    aucs.push_back(area / (n * t));
  }
  return aucs;
}

}  // namespace ramap
