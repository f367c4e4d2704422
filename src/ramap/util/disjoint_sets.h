// Union-find over dense indices 0..size-1.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ramap {

// The root of a set is its smallest index, so the result does not depend on the order of the
// unions.
class DisjointSets {
 public:
  explicit DisjointSets(size_t size) : parent_(size) {
    for (size_t k = 0; k < size; ++k) parent_[k] = static_cast<uint32_t>(k);
  }
  uint32_t Find(uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];  // path halving
      x = parent_[x];
    }
    return x;
  }
  // Returns whether a and b were in different sets.
  bool Union(uint32_t a, uint32_t b) {
    const uint32_t ra = Find(a), rb = Find(b);
    if (ra == rb) return false;
    parent_[std::max(ra, rb)] = std::min(ra, rb);
    return true;
  }
  // The root of every element in one pass, without path chasing: a parent is never larger than
  // its child (roots are the smallest index and path halving only moves links down), so an
  // element's parent has its root already when the elements are taken in increasing order.
  std::vector<uint32_t> Roots() const {
    std::vector<uint32_t> roots(parent_.size());
    for (size_t x = 0; x < parent_.size(); ++x) {
      roots[x] = parent_[x] == x ? uint32_t(x) : roots[parent_[x]];
    }
    return roots;
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace ramap
