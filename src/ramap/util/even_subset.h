// At most a given number of items, evenly spaced through a list: how stages that gain little from
// thousands of matches take a bounded, unbiased share of them.
#pragma once

#include <cstddef>
#include <vector>

namespace ramap {

// Items k * size / max_count for k < max_count, in order; all of them when there are at most
// max_count (or max_count is 0).
template <typename T>
std::vector<T> EvenSubset(const std::vector<T>& items, size_t max_count) {
  if (max_count == 0 || items.size() <= max_count) return items;
  std::vector<T> subset;
  subset.reserve(max_count);
  for (size_t k = 0; k < max_count; ++k) subset.push_back(items[k * items.size() / max_count]);
  return subset;
}

}  // namespace ramap
