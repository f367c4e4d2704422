// Photos of something else whose pairs verify, joined to the scene through one photo that shows
// both (a print of the scene on a poster): they end in their own model, not inside the scene's
// (mapper/components.h, graph/rigid_clusters.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "ramap/mapper/mapper.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

constexpr uint32_t kOffset = 100;  // the distractors' image ids: 101, 102, ...

// `scene`'s database with `other`'s images added as ids kOffset + id (their own camera), and its
// first image made a photo that also shows what scene image `shown` sees: `shown`'s keypoints are
// appended to it, and each scene image with a pair to `shown` (and a lower id) gets a pair to it
// with that pair's matches and geometry.
FeatureDatabase WithPosterDistractors(const SyntheticScene& scene, const SyntheticScene& other,
                                      uint32_t shown, int* num_poster_pairs) {
  FeatureDatabase database = scene.database;
  Camera camera = other.database.cameras.begin()->second;
  camera.camera_id = 2;
  database.cameras[2] = camera;
  for (const auto& [id, image] : other.database.images) {
    Image copy = image;
    copy.image_id = kOffset + id;
    copy.camera_id = 2;
    copy.name = "distractor_" + std::to_string(id) + ".png";
    database.images[copy.image_id] = copy;
    database.keypoints[copy.image_id] = other.database.keypoints.at(id);
  }
  for (const auto& [pair_id, geometry] : other.database.two_view_geometries) {
    TwoViewGeometry copy = geometry;
    copy.image_id1 += kOffset;
    copy.image_id2 += kOffset;
    database.two_view_geometries[ImagePairToPairId(copy.image_id1, copy.image_id2)] = copy;
  }
  const uint32_t poster = kOffset + other.database.images.begin()->first;
  Keypoints& keypoints = database.keypoints.at(poster);
  const uint32_t appended = static_cast<uint32_t>(keypoints.size());
  const Keypoints& shown_keypoints = scene.database.keypoints.at(shown);
  for (size_t row = 0; row < shown_keypoints.size(); ++row) {
    for (int col = 0; col < keypoints.num_cols; ++col) {
      keypoints.data.push_back(col < shown_keypoints.num_cols
                                   ? shown_keypoints.data[row * shown_keypoints.num_cols + col]
                                   : 0.0f);
    }
  }
  *num_poster_pairs = 0;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    if (geometry.image_id2 != shown || geometry.inlier_matches.size() < 30) continue;
    TwoViewGeometry copy = geometry;
    copy.image_id2 = poster;
    for (FeatureMatch& match : copy.inlier_matches) match.point2D_idx2 += appended;
    database.two_view_geometries[ImagePairToPairId(copy.image_id1, poster)] = copy;
    ++*num_poster_pairs;
  }
  return database;
}

TEST(ComponentsDistractor, PhotosOfSomethingElseJoinedThroughOnePhotoStayOutOfTheScene) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(21));
  SyntheticSceneOptions other_options = test::NoisyCollection(22);
  other_options.num_images = 5;
  other_options.object_radius = 1.0;  // a different object at another size
  const SyntheticScene other = BuildSyntheticScene(other_options);
  int num_poster_pairs = 0;
  const FeatureDatabase database =
      WithPosterDistractors(scene, other, /*shown=*/8, &num_poster_pairs);
  ASSERT_GE(num_poster_pairs, 2);

  const MapperResult result = RunMapper(database, MapperOptions(), "scene with distractors");
  ASSERT_GE(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  int scene_images = 0, distractors = 0;
  for (const auto& [id, image] : model.images) (id > kOffset ? distractors : scene_images) += 1;
  EXPECT_EQ(scene_images, static_cast<int>(scene.database.images.size()));
  // The poster photo itself is consistent with the scene (its scene part is a copy of a view):
  // no geometry tells it out. The other distractors must not be in the scene's model.
  EXPECT_LE(distractors, 1);
  // They are reconstructed in a model of their own.
  ASSERT_EQ(result.reconstructions.size(), 2u);
  for (const auto& [id, image] : result.reconstructions[1].images) EXPECT_GT(id, kOffset);
  EXPECT_GE(result.reconstructions[1].images.size(), 4u);
  const auto cut = std::find_if(result.summary.dropped_edges.begin(),
                                result.summary.dropped_edges.end(), [](const DroppedItem& item) {
                                  return item.reason.find("through one image") != std::string::npos;
                                });
  EXPECT_NE(cut, result.summary.dropped_edges.end());
}

}  // namespace
}  // namespace ramap
