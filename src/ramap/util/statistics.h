// Order statistics shared by the stages.
#pragma once

#include <vector>

namespace ramap {

// The upper median (element size / 2 in sorted order) of a non-empty vector, by copy; throws
// std::invalid_argument when empty.
double Median(std::vector<double> values);

}  // namespace ramap
