#include "ramap/geometry/pair_correspondences.h"

#include "ramap/geometry/camera_projection.h"
#include "ramap/geometry/correspondence_sampling.h"

namespace ramap {
namespace {

Eigen::Vector3d BearingOf(const PairImage& image, uint32_t point2D_idx) {
  if (image.bearings != nullptr) return (*image.bearings)[point2D_idx];
  return PixelToBearing(image.camera, image.keypoints.xy(point2D_idx));
}

}  // namespace

TwoViewCorrespondences PairCorrespondences(const PairImage& image1, const PairImage& image2,
                                           const TwoViewGeometry& geometry, double focal_length_px,
                                           bool use_descriptor_ratios,
                                           std::vector<uint32_t>* kept_indices) {
  TwoViewCorrespondences c;
  c.width1 = static_cast<int>(image1.camera.width);
  c.height1 = static_cast<int>(image1.camera.height);
  c.width2 = static_cast<int>(image2.camera.width);
  c.height2 = static_cast<int>(image2.camera.height);
  c.focal_length_px = focal_length_px;
  const bool use_ratios = use_descriptor_ratios && !geometry.inlier_ratios.empty();
  for (size_t k = 0; k < geometry.inlier_matches.size(); ++k) {
    const FeatureMatch& match = geometry.inlier_matches[k];
    const Eigen::Vector3d bearing1 = BearingOf(image1, match.point2D_idx1);
    const Eigen::Vector3d bearing2 = BearingOf(image2, match.point2D_idx2);
    if (!bearing1.allFinite() || !bearing2.allFinite()) continue;
    if (kept_indices != nullptr) kept_indices->push_back(static_cast<uint32_t>(k));
    if (use_ratios) c.confidence.push_back(geometry.inlier_ratios[k]);
    c.bearings1.push_back(bearing1);
    c.bearings2.push_back(bearing2);
    c.pixels1.push_back(image1.keypoints.xy(match.point2D_idx1));
    c.pixels2.push_back(image2.keypoints.xy(match.point2D_idx2));
  }
  // Without descriptor ratios (a COLMAP-matched database), the Sampson error under the F every
  // verified pair stores ranks the matches.
  if (!use_ratios && !geometry.F.isZero()) {
    c.confidence = SampsonErrors(geometry.F, c.pixels1, c.pixels2);
  }
  return c;
}

}  // namespace ramap
