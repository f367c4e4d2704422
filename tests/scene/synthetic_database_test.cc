// The synthetic scene through the COLMAP database writer and reader: what `ramap synthesize`
// writes must read back unchanged.
#include <gtest/gtest.h>

#include "ramap/io/colmap_database.h"
#include "ramap/scene/synthetic.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(SyntheticDatabase, RoundTripsThroughTheColmapDatabase) {
  SyntheticSceneOptions options;
  options.num_images = 15;
  options.num_points = 600;
  options.num_outlier_pairs = 2;
  const SyntheticScene scene = BuildSyntheticScene(options);
  test::TempDir dir;
  WriteColmapDatabase(scene.database, dir / "database.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "database.db");

  ASSERT_EQ(read.cameras.size(), 1u);
  EXPECT_EQ(read.cameras.at(1).params, scene.database.cameras.at(1).params);
  ASSERT_EQ(read.images.size(), scene.database.images.size());
  for (const auto& [image_id, image] : scene.database.images) {
    EXPECT_EQ(read.images.at(image_id).name, image.name);
    EXPECT_EQ(read.keypoints.at(image_id).data, scene.database.keypoints.at(image_id).data);
  }
  ASSERT_EQ(read.matches.size(), scene.database.matches.size());
  for (const auto& [pair_id, matches] : scene.database.matches) {
    ASSERT_EQ(read.matches.at(pair_id).size(), matches.size());
  }
  ASSERT_EQ(read.two_view_geometries.size(), scene.database.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    const TwoViewGeometry& other = read.two_view_geometries.at(pair_id);
    EXPECT_EQ(other.config, geometry.config);
    EXPECT_EQ(other.inlier_matches.size(), geometry.inlier_matches.size());
    EXPECT_TRUE(other.E.isApprox(geometry.E, 1e-12));
    EXPECT_LT(other.cam2_from_cam1.rotation.angularDistance(geometry.cam2_from_cam1.rotation),
              1e-12);
  }
}

}  // namespace
}  // namespace ramap
