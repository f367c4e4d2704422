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

Eigen::Vector3d MedianPoint(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d median;
  std::vector<double> values(points.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (size_t k = 0; k < points.size(); ++k) values[k] = points[k](axis);
    median(axis) = Median(values);
  }
  return median;
}

}  // namespace ramap
