#include "ramap/features/descriptor_matching.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "ramap/util/cblas.h"

namespace ramap {
namespace {

// The two nearest columns of every row of a distance matrix (ratio test) and the nearest row of
// every column (cross check), gathered while the rows stream past. Ties go to the first index, so
// the fast and the plain path agree exactly.
template <typename Distance>
struct NearestNeighbours {
  std::vector<int> best2;         // per row of 1: nearest row of 2
  std::vector<Distance> first2;   // its distance
  std::vector<Distance> second2;  // the second-nearest distance
  std::vector<int> best1;         // per row of 2: nearest row of 1
  std::vector<Distance> best1_distance;

  NearestNeighbours(size_t n1, size_t n2, Distance infinity)
      : best2(n1, -1),
        first2(n1, infinity),
        second2(n1, infinity),
        best1(n2, -1),
        best1_distance(n2, infinity) {}

  void Add(size_t i, size_t j, Distance d) {
    if (d < first2[i]) {
      second2[i] = first2[i], first2[i] = d, best2[i] = static_cast<int>(j);
    } else if (d < second2[i]) {
      second2[i] = d;
    }
    if (d < best1_distance[j]) best1_distance[j] = d, best1[j] = static_cast<int>(i);
  }

  // Add(i, j, row[j]) for every j in order (the same result, ties included).
  void AddRow(size_t i, const Distance* row, size_t n2) {
    Distance first = first2[i], second = second2[i];
    int first_j = best2[i];
    for (size_t j = 0; j < n2; ++j) {
      if (!(row[j] < second)) continue;
      if (row[j] < first) {
        second = first, first = row[j], first_j = static_cast<int>(j);
      } else {
        second = row[j];
      }
    }
    first2[i] = first, second2[i] = second, best2[i] = first_j;
    Distance* column_best = best1_distance.data();
    int* column_row = best1.data();
    const int row_index = static_cast<int>(i);
    for (size_t j = 0; j < n2; ++j) {
      const bool closer = row[j] < column_best[j];
      column_best[j] = closer ? row[j] : column_best[j];
      column_row[j] = closer ? row_index : column_row[j];
    }
  }
};

// The matches that pass the ratio test on `distance` (a monotone map of the stored values to the
// metric: sqrt for squared L2) and, if asked, the cross check.
template <typename Distance, typename Metric>
std::vector<FeatureMatch> AcceptMatches(const NearestNeighbours<Distance>& nn,
                                        const DescriptorMatchingOptions& options, Metric distance,
                                        std::vector<float>* ratios) {
  std::vector<FeatureMatch> matches;
  for (size_t i = 0; i < nn.best2.size(); ++i) {
    if (nn.best2[i] < 0) continue;
    const double first = distance(nn.first2[i]), second = distance(nn.second2[i]);
    // Passing the test makes second > 0.
    if (!(first < options.max_ratio * second)) continue;
    if (options.cross_check && nn.best1[nn.best2[i]] != static_cast<int>(i)) continue;
    matches.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(nn.best2[i])});
    if (ratios != nullptr) ratios->push_back(static_cast<float>(first / second));
  }
  return matches;
}

// Hamming distances of 256-bit descriptors, one pass over the distance matrix: much quicker
// than two OpenCV knnMatch calls on ORB's 32 bytes, which each compute the whole matrix.
std::vector<FeatureMatch> MatchBinary(const Descriptors& descriptors1,
                                      const Descriptors& descriptors2,
                                      const DescriptorMatchingOptions& options,
                                      std::vector<float>* ratios) {
  const size_t n1 = descriptors1.size(), n2 = descriptors2.size();
  auto words = [](const Descriptors& d) {
    std::vector<uint64_t> w(d.size() * 4);
    std::memcpy(w.data(), d.data.data(), d.data.size());
    return w;
  };
  const std::vector<uint64_t> w1 = words(descriptors1), w2 = words(descriptors2);
  NearestNeighbours<int> nn(n1, n2, 257);
  for (size_t i = 0; i < n1; ++i) {
    const uint64_t* a = &w1[4 * i];
    for (size_t j = 0; j < n2; ++j) {
      const uint64_t* b = &w2[4 * j];
      nn.Add(i, j,
             __builtin_popcountll(a[0] ^ b[0]) + __builtin_popcountll(a[1] ^ b[1]) +
                 __builtin_popcountll(a[2] ^ b[2]) + __builtin_popcountll(a[3] ^ b[3]));
    }
  }
  return AcceptMatches(
      nn, options, [](int d) { return static_cast<double>(d); }, ratios);
}

std::vector<float> AsFloats(const Descriptors& descriptors) {
  return std::vector<float>(descriptors.data.begin(), descriptors.data.end());
}

std::vector<float> SquaredNorms(const std::vector<float>& rows, int num_cols) {
  std::vector<float> norms(rows.size() / num_cols);
  for (size_t i = 0; i < norms.size(); ++i) {
    const float* row = &rows[i * num_cols];
    float sum = 0;
    for (int c = 0; c < num_cols; ++c) sum += row[c] * row[c];
    norms[i] = sum;
  }
  return norms;
}

// Squared L2 distances by SGEMM, a block of rows of 1 at a time. For 8-bit descriptors of up to
// 128 columns every product and sum is an integer below 2^24, so float holds them exactly and the
// result equals the plain loop's, ties included.
std::vector<FeatureMatch> MatchFloat(const Descriptors& descriptors1,
                                     const Descriptors& descriptors2,
                                     const DescriptorMatchingOptions& options,
                                     std::vector<float>* ratios) {
  const int n1 = static_cast<int>(descriptors1.size()), n2 = static_cast<int>(descriptors2.size());
  const int dim = descriptors1.num_cols;
  const std::vector<float> a = AsFloats(descriptors1), b = AsFloats(descriptors2);
  const std::vector<float> norms1 = SquaredNorms(a, dim), norms2 = SquaredNorms(b, dim);
  constexpr int kBlockRows = 512;  // a 512 x 8192 block of products is 16 MB
  std::vector<float> products(static_cast<size_t>(std::min(n1, kBlockRows)) * n2);
  NearestNeighbours<float> nn(n1, n2, FLT_MAX);
  for (int begin = 0; begin < n1; begin += kBlockRows) {
    const int rows = std::min(kBlockRows, n1 - begin);
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, rows, n2, dim, 1.0f,
                &a[static_cast<size_t>(begin) * dim], dim, b.data(), dim, 0.0f, products.data(),
                n2);
    for (int r = 0; r < rows; ++r) {
      const int i = begin + r;
      float* row = &products[static_cast<size_t>(r) * n2];
      // Simple passes the compiler vectorises, rather than one branchy one: the distances, then
      // the row's two nearest and the columns' nearest.
      for (int j = 0; j < n2; ++j) row[j] = std::max(0.0f, norms1[i] + norms2[j] - 2.0f * row[j]);
      nn.AddRow(i, row, n2);
    }
  }
  return AcceptMatches(
      nn, options, [](float d) { return std::sqrt(static_cast<double>(d)); }, ratios);
}

// Squared L2 distances by the plain loop, in exact integers.
std::vector<FeatureMatch> MatchFloatByLoop(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const DescriptorMatchingOptions& options,
                                           std::vector<float>* ratios) {
  const size_t n1 = descriptors1.size(), n2 = descriptors2.size();
  const int dim = descriptors1.num_cols;
  NearestNeighbours<int64_t> nn(n1, n2, std::numeric_limits<int64_t>::max());
  for (size_t i = 0; i < n1; ++i) {
    for (size_t j = 0; j < n2; ++j) {
      int64_t d = 0;
      for (int c = 0; c < dim; ++c) {
        const int64_t diff =
            int64_t{descriptors1.data[i * dim + c]} - descriptors2.data[j * dim + c];
        d += diff * diff;
      }
      nn.Add(i, j, d);
    }
  }
  return AcceptMatches(
      nn, options, [](int64_t d) { return std::sqrt(static_cast<double>(d)); }, ratios);
}

// Matches by `float_path` for float descriptors; Hamming's loop for binary ones; none when the
// two sets cannot be compared or the second has fewer than two rows (no ratio test).
template <typename FloatPath>
std::vector<FeatureMatch> Match(const Descriptors& descriptors1, const Descriptors& descriptors2,
                                const DescriptorMatchingOptions& options,
                                std::vector<float>* ratios, FloatPath float_path) {
  if (ratios != nullptr) ratios->clear();
  if (descriptors1.num_cols != descriptors2.num_cols || descriptors1.size() == 0 ||
      descriptors2.size() < 2) {
    return {};
  }
  if (descriptors1.num_cols == 32) return MatchBinary(descriptors1, descriptors2, options, ratios);
  return float_path(descriptors1, descriptors2, options, ratios);
}

}  // namespace

std::vector<FeatureMatch> MatchDescriptors(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const DescriptorMatchingOptions& options,
                                           std::vector<float>* ratios) {
  return Match(descriptors1, descriptors2, options, ratios, MatchFloat);
}

std::vector<FeatureMatch> MatchDescriptorsByLoop(const Descriptors& descriptors1,
                                                 const Descriptors& descriptors2,
                                                 const DescriptorMatchingOptions& options,
                                                 std::vector<float>* ratios) {
  return Match(descriptors1, descriptors2, options, ratios, MatchFloatByLoop);
}

Descriptors LargestScaleDescriptors(const Keypoints& keypoints, const Descriptors& descriptors,
                                    int count) {
  const size_t n = std::min(keypoints.size(), descriptors.size());
  if (static_cast<int>(n) <= count) return descriptors;
  // The scale: column 3 of x, y, scale, orientation; the square root of the affine shape's
  // determinant (COLMAP's x, y, a11, a12, a21, a22). Without either, an even subset.
  const int cols = keypoints.num_cols;
  std::vector<float> scales(n, 0.0f);
  for (size_t k = 0; k < n && (cols == 4 || cols == 6); ++k) {
    const float* row = &keypoints.data[k * cols];
    scales[k] = cols == 4 ? row[2] : std::sqrt(std::abs(row[2] * row[5] - row[3] * row[4]));
  }
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  if (cols == 4 || cols == 6) {
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return scales[a] > scales[b]; });
  } else {
    for (int k = 0; k < count; ++k) order[k] = k * n / count;
  }
  Descriptors subset;
  subset.num_cols = descriptors.num_cols;
  for (int k = 0; k < count; ++k) {
    const auto row = descriptors.data.begin() + order[k] * descriptors.num_cols;
    subset.data.insert(subset.data.end(), row, row + descriptors.num_cols);
  }
  return subset;
}

}  // namespace ramap
