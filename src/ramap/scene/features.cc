#include "ramap/scene/features.h"

#include <algorithm>

namespace ramap {

uint64_t ImagePairToPairId(uint32_t image_id1, uint32_t image_id2) {
  const uint64_t i = std::min(image_id1, image_id2);
  const uint64_t j = std::max(image_id1, image_id2);
  return i * kMaxNumImages + j;
}

std::pair<uint32_t, uint32_t> PairIdToImagePair(uint64_t pair_id) {
  const uint32_t j = static_cast<uint32_t>(pair_id % kMaxNumImages);
  const uint32_t i = static_cast<uint32_t>((pair_id - j) / kMaxNumImages);
  return {i, j};
}

TwoViewGeometry InvertTwoViewGeometry(const TwoViewGeometry& geometry) {
  TwoViewGeometry inverted = geometry;
  std::swap(inverted.image_id1, inverted.image_id2);
  for (FeatureMatch& match : inverted.inlier_matches) {
    std::swap(match.point2D_idx1, match.point2D_idx2);
  }
  inverted.F = geometry.F.transpose();
  inverted.E = geometry.E.transpose();
  // An all-zero H means "not estimated" and stays so.
  if (!geometry.H.isZero()) inverted.H = geometry.H.inverse();
  inverted.cam2_from_cam1 = geometry.cam2_from_cam1.Inverse();
  return inverted;
}

}  // namespace ramap
