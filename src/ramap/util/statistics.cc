#include "ramap/util/statistics.h"

#include <algorithm>
#include <stdexcept>

namespace ramap {

double Median(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("Median of an empty vector");
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

}  // namespace ramap
