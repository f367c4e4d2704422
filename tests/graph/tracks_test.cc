#include "ramap/graph/tracks.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

TwoViewGeometry Pair(uint32_t i, uint32_t j, std::vector<FeatureMatch> matches) {
  TwoViewGeometry g;
  g.image_id1 = i;
  g.image_id2 = j;
  g.config = TwoViewConfig::kCalibrated;
  g.inlier_matches = std::move(matches);
  return g;
}

TEST(Tracks, ChainsMatchesAcrossPairs) {
  std::map<uint64_t, TwoViewGeometry> geometries;
  geometries[ImagePairToPairId(1, 2)] = Pair(1, 2, {{10, 20}, {11, 21}});
  geometries[ImagePairToPairId(2, 3)] = Pair(2, 3, {{20, 30}});
  TrackBuildSummary summary;
  const std::vector<Track> tracks = BuildTracks(geometries, {}, {}, &summary);
  ASSERT_EQ(tracks.size(), 2u);
  ASSERT_EQ(tracks[0].size(), 3u);  // 1:10 - 2:20 - 3:30
  EXPECT_EQ(tracks[0][0].image_id, 1u);
  EXPECT_EQ(tracks[0][0].point2D_idx, 10u);
  EXPECT_EQ(tracks[0][2].image_id, 3u);
  EXPECT_EQ(tracks[0][2].point2D_idx, 30u);
  EXPECT_EQ(tracks[1].size(), 2u);  // 1:11 - 2:21
  EXPECT_EQ(summary.num_tracks, 2);
}

TEST(Tracks, DropsTrackThatSeesAnImageTwice) {
  std::map<uint64_t, TwoViewGeometry> geometries;
  // 1:5 - 2:7 - 3:9 - 1:6 links two keypoints of image 1.
  geometries[ImagePairToPairId(1, 2)] = Pair(1, 2, {{5, 7}});
  geometries[ImagePairToPairId(2, 3)] = Pair(2, 3, {{7, 9}});
  geometries[ImagePairToPairId(1, 3)] = Pair(1, 3, {{6, 9}, {8, 8}});
  TrackBuildSummary summary;
  const std::vector<Track> tracks = BuildTracks(geometries, {}, {}, &summary);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0][0].point2D_idx, 8u);
  EXPECT_EQ(summary.num_conflicting_tracks, 1);
}

TEST(Tracks, UsesOnlyTheChosenPairsAndMinimumLength) {
  std::map<uint64_t, TwoViewGeometry> geometries;
  geometries[ImagePairToPairId(1, 2)] = Pair(1, 2, {{0, 0}});
  geometries[ImagePairToPairId(2, 3)] = Pair(2, 3, {{0, 0}});
  EXPECT_EQ(BuildTracks(geometries, {ImagePairToPairId(1, 2)})[0].size(), 2u);
  TrackBuildOptions options;
  options.min_track_length = 3;
  EXPECT_EQ(BuildTracks(geometries, {}, options).size(), 1u);
  EXPECT_TRUE(BuildTracks(geometries, {ImagePairToPairId(1, 2)}, options).empty());
}

}  // namespace
}  // namespace ramap
