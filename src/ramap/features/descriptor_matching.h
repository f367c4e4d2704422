// Putative matches of two images' descriptors by brute force: every descriptor of one image against
// every descriptor of the other, the two nearest kept for Lowe's ratio test and the nearest in the
// other direction for the cross check.
#pragma once

#include <vector>

#include "ramap/scene/features.h"

namespace ramap {

struct DescriptorMatchingOptions {
  // Lowe's ratio test: nearest < max_ratio * second nearest (COLMAP's SiftMatching default, 0.8).
  double max_ratio = 0.8;
  // Mutual nearest neighbours only (COLMAP's default, on).
  bool cross_check = true;
};

// Hamming distance for 32-byte binary descriptors (ORB), L2 otherwise (SIFT). With `ratios`, also
// each match's nearest / second-nearest distance ratio (its confidence; lower is better).
// Float descriptors are compared through one matrix product per block of rows (the BLAS's SGEMM),
// |a - b|^2 = |a|^2 + |b|^2 - 2 a.b, which runs at the GEMM's speed rather than a distance loop's;
// the caller decides how many BLAS threads that uses (SingleBlasThread when pairs run in parallel).
std::vector<FeatureMatch> MatchDescriptors(const Descriptors& descriptors1,
                                           const Descriptors& descriptors2,
                                           const DescriptorMatchingOptions& options,
                                           std::vector<float>* ratios = nullptr);

// The same matches by the plain definition (a distance loop per pair of descriptors): the reference
// the fast path is tested against.
std::vector<FeatureMatch> MatchDescriptorsByLoop(const Descriptors& descriptors1,
                                                 const Descriptors& descriptors2,
                                                 const DescriptorMatchingOptions& options,
                                                 std::vector<float>* ratios = nullptr);

// The descriptors of an image's `count` largest-scale keypoints: the features most likely to be
// seen again from further away or closer. All of them when there are no more than `count`; an even
// subset when the keypoints have no scale (two columns).
Descriptors LargestScaleDescriptors(const Keypoints& keypoints, const Descriptors& descriptors,
                                    int count);

}  // namespace ramap
