// Order statistics shared by the stages.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace ramap {

// The upper median (element size / 2 in sorted order) of a non-empty vector, by copy; throws
// std::invalid_argument when empty.
double Median(std::vector<double> values);

// The upper median of each coordinate of a non-empty set of points; throws std::invalid_argument
// when empty.
Eigen::Vector3d MedianPoint(const std::vector<Eigen::Vector3d>& points);

}  // namespace ramap
