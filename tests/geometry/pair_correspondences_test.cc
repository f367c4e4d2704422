// The assembly of a pair's matches shared by the mapper and the matcher: the same correspondences
// whether the bearings are given or computed, matches without a bearing left out with their
// confidence, and the two rankings.
#include "ramap/geometry/pair_correspondences.h"

#include <gtest/gtest.h>

#include <limits>

#include "ramap/geometry/camera_projection.h"

namespace ramap {
namespace {

struct TwoImages {
  Camera camera;
  Keypoints keypoints1, keypoints2;
  TwoViewGeometry geometry;
};

// Four matches between two VGA images, F a pure horizontal shift of 10 px.
TwoImages FourMatches() {
  TwoImages images;
  images.camera.model = CameraModel::kPinhole;
  images.camera.width = 640;
  images.camera.height = 480;
  images.camera.params = {500, 500, 320, 240};
  images.keypoints1.data = {100, 100, 200, 150, 300, 200, 400, 260};
  images.keypoints2.data = {110, 100, 210, 151, 310, 200, 410, 262};
  for (uint32_t k = 0; k < 4; ++k) images.geometry.inlier_matches.push_back({k, k});
  images.geometry.inlier_ratios = {0.4f, 0.5f, 0.6f, 0.7f};
  // x2 = x1 + (10, 0): the epipolar lines are the rows, F = [t]x for t = (1, 0, 0) in pixels.
  images.geometry.F << 0, 0, 0, 0, 0, -1, 0, 1, 0;
  return images;
}

TEST(PairCorrespondences, GivenAndComputedBearingsGiveTheSameMatches) {
  const TwoImages images = FourMatches();
  std::vector<Eigen::Vector3d> bearings1, bearings2;
  for (size_t k = 0; k < 4; ++k) {
    bearings1.push_back(PixelToBearing(images.camera, images.keypoints1.xy(k)));
    bearings2.push_back(PixelToBearing(images.camera, images.keypoints2.xy(k)));
  }
  const TwoViewCorrespondences computed =
      PairCorrespondences({images.camera, images.keypoints1}, {images.camera, images.keypoints2},
                          images.geometry, 500, false);
  const TwoViewCorrespondences given = PairCorrespondences(
      {images.camera, images.keypoints1, &bearings1},
      {images.camera, images.keypoints2, &bearings2}, images.geometry, 500, false);
  ASSERT_EQ(computed.size(), 4u);
  EXPECT_EQ(computed.bearings1, given.bearings1);
  EXPECT_EQ(computed.bearings2, given.bearings2);
  EXPECT_EQ(computed.pixels2[1], Eigen::Vector2d(210, 151));
  EXPECT_EQ(computed.width2, 640);
  EXPECT_EQ(computed.focal_length_px, 500);
  // Sampson errors under F: zero on the row, non-zero off it.
  ASSERT_EQ(computed.confidence.size(), 4u);
  EXPECT_NEAR(computed.confidence[0], 0.0, 1e-12);
  EXPECT_GT(computed.confidence[1], 0.1);
}

TEST(PairCorrespondences, AMatchWithoutBearingIsLeftOutWithItsRatio) {
  const TwoImages images = FourMatches();
  std::vector<Eigen::Vector3d> bearings1(4, Eigen::Vector3d::UnitZ());
  std::vector<Eigen::Vector3d> bearings2(4, Eigen::Vector3d::UnitZ());
  bearings2[1].x() = std::numeric_limits<double>::quiet_NaN();  // past a distortion's fold
  const TwoViewCorrespondences c = PairCorrespondences(
      {images.camera, images.keypoints1, &bearings1},
      {images.camera, images.keypoints2, &bearings2}, images.geometry, 500, true);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.confidence, (std::vector<double>{0.4f, 0.6f, 0.7f}));
  EXPECT_EQ(c.pixels1[1], Eigen::Vector2d(300, 200));
}

TEST(PairCorrespondences, WithoutRatiosOrFundamentalMatrixNoMatchRanksFirst) {
  TwoImages images = FourMatches();
  images.geometry.inlier_ratios.clear();
  images.geometry.F.setZero();
  const TwoViewCorrespondences c =
      PairCorrespondences({images.camera, images.keypoints1}, {images.camera, images.keypoints2},
                          images.geometry, 500, true);
  EXPECT_EQ(c.size(), 4u);
  EXPECT_TRUE(c.confidence.empty());
}

}  // namespace
}  // namespace ramap
