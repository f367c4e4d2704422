#include "ramap/scene/features.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

TEST(PairId, MatchesColmapConventionBothWays) {
  EXPECT_EQ(ImagePairToPairId(1, 2), 2147483647ULL + 2);
  EXPECT_EQ(ImagePairToPairId(2, 1), ImagePairToPairId(1, 2));
  const auto [i, j] = PairIdToImagePair(ImagePairToPairId(7, 3));
  EXPECT_EQ(i, 3u);
  EXPECT_EQ(j, 7u);
  const auto [a, b] = PairIdToImagePair(ImagePairToPairId(2147483646u, 2147483645u));
  EXPECT_EQ(a, 2147483645u);
  EXPECT_EQ(b, 2147483646u);
}

TEST(TwoViewGeometry, InvertingTwiceGivesTheOriginal) {
  TwoViewGeometry g;
  g.image_id1 = 1;
  g.image_id2 = 2;
  g.inlier_matches = {{3, 4}, {5, 6}};
  g.cam2_from_cam1 = Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
                             Eigen::Vector3d(0.1, -0.2, 0.9));
  g.F = Eigen::Matrix3d::Random();
  g.H = Eigen::Matrix3d::Random() + 3 * Eigen::Matrix3d::Identity();
  const TwoViewGeometry inv = InvertTwoViewGeometry(g);
  EXPECT_EQ(inv.image_id1, 2u);
  EXPECT_EQ(inv.inlier_matches[0].point2D_idx1, 4u);
  EXPECT_TRUE(inv.F.isApprox(g.F.transpose()));
  // cam1_from_cam2 composed with cam2_from_cam1 is the identity.
  const Rigid3d identity = inv.cam2_from_cam1 * g.cam2_from_cam1;
  EXPECT_LT(identity.translation.norm(), 1e-12);
  EXPECT_LT(identity.rotation.angularDistance(Eigen::Quaterniond::Identity()), 1e-12);
  const TwoViewGeometry back = InvertTwoViewGeometry(inv);
  EXPECT_TRUE(back.H.isApprox(g.H, 1e-12));
}

}  // namespace
}  // namespace ramap
