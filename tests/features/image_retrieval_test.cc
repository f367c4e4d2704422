// Image retrieval: one unit VLAD vector per image in the order asked, alike for images that share
// features, and each image's most similar others as pairs (smaller id first, each once, in order
// of first appearance, beyond the index gap asked).
#include "ramap/features/image_retrieval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// Hand-made unit descriptors in two dimensions, at the given angles (degrees), for image ids 10,
// 20, 30...: the cosine similarity of two images is the cosine of their angle difference.
GlobalDescriptors AtAngles(const std::vector<double>& angles_deg) {
  GlobalDescriptors descriptors;
  descriptors.dimension = 2;
  for (size_t k = 0; k < angles_deg.size(); ++k) {
    descriptors.image_ids.push_back(static_cast<uint32_t>(10 * (k + 1)));
    descriptors.rows.push_back(static_cast<float>(std::cos(angles_deg[k] * M_PI / 180)));
    descriptors.rows.push_back(static_cast<float>(std::sin(angles_deg[k] * M_PI / 180)));
  }
  return descriptors;
}

using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;

TEST(ImageRetrieval, MostSimilarFirstEachPairOnceSmallerIdFirst) {
  // Images 10..50 at 0, 10, 50, 55, 180 degrees.
  const GlobalDescriptors descriptors = AtAngles({0, 10, 50, 55, 180});
  // One neighbour each: 10->20, 20->10 (already there), 30->40, 40->30, 50->40 (cos 125 > cos 130).
  EXPECT_EQ(MostSimilarPairs(descriptors, 1), (Pairs{{10, 20}, {30, 40}, {40, 50}}));
  // Two each: 10: 20, 30; 20: 10, 30; 30: 40, 20; 40: 30, 20; 50: 40, 30.
  EXPECT_EQ(MostSimilarPairs(descriptors, 2),
            (Pairs{{10, 20}, {10, 30}, {20, 30}, {30, 40}, {20, 40}, {40, 50}, {30, 50}}));
}

TEST(ImageRetrieval, NeighboursWithinTheIndexGapAreSkipped) {
  const GlobalDescriptors descriptors = AtAngles({0, 10, 50, 55, 180});
  // Positions more than 2 apart only: 10 with 40 or 50, 20 with 50, and back.
  EXPECT_EQ(MostSimilarPairs(descriptors, 1, 2), (Pairs{{10, 40}, {20, 50}}));
  EXPECT_EQ(MostSimilarPairs(descriptors, 3, 3), (Pairs{{10, 50}}));  // the only ones 4 apart
  EXPECT_TRUE(MostSimilarPairs(descriptors, 0).empty());
  EXPECT_TRUE(MostSimilarPairs(AtAngles({0}), 3).empty());
}

// A 12-view orbit with SIFT-like descriptors of its points and four columns per keypoint (scale
// and orientation), as extraction stores them.
SyntheticScene OrbitWithDescriptors() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kCircle, 12);
  options.num_points = 1000;
  options.keypoint_columns = 4;
  SyntheticScene scene = BuildSyntheticScene(options);
  AddSyntheticDescriptors(SyntheticDescriptorOptions(), &scene);
  return scene;
}

ImageRetrievalOptions SmallVocabulary() {
  ImageRetrievalOptions options;
  options.num_words = 16;
  options.max_features_per_image = 300;
  options.num_kmeans_iterations = 5;
  return options;
}

double Dot(const GlobalDescriptors& descriptors, size_t a, size_t b) {
  double sum = 0;
  for (int k = 0; k < descriptors.dimension; ++k) {
    sum += double{descriptors.row(a)[k]} * descriptors.row(b)[k];
  }
  return sum;
}

TEST(ImageRetrieval, UnitVectorsInTheOrderAskedAlikeWhereViewsOverlap) {
  const SyntheticScene scene = OrbitWithDescriptors();
  const std::vector<uint32_t> ids = {12, 1, 2, 7};
  const GlobalDescriptors descriptors =
      ComputeGlobalDescriptors(scene.database, ids, SmallVocabulary(), 2);
  EXPECT_EQ(descriptors.image_ids, ids);
  EXPECT_EQ(descriptors.dimension, 16 * 128);
  ASSERT_EQ(descriptors.rows.size(), ids.size() * 16 * 128);
  for (size_t k = 0; k < ids.size(); ++k) {
    EXPECT_NEAR(Dot(descriptors, k, k), 1.0, 1e-5) << "image " << ids[k];  // float sums
  }
  // On the orbit, views 1 and 2 and views 1 and 12 are neighbours; view 7 is opposite view 1 and
  // shares no point with it.
  EXPECT_GT(Dot(descriptors, 1, 2), Dot(descriptors, 1, 3));
  EXPECT_GT(Dot(descriptors, 1, 0), Dot(descriptors, 1, 3));
  // The same input gives the same vectors, whatever the threads.
  EXPECT_EQ(ComputeGlobalDescriptors(scene.database, ids, SmallVocabulary(), 1).rows,
            descriptors.rows);
}

TEST(ImageRetrieval, EachViewsMostSimilarAreItsNeighboursOnTheOrbit) {
  const SyntheticScene scene = OrbitWithDescriptors();
  std::vector<uint32_t> ids;
  for (uint32_t id = 1; id <= 12; ++id) ids.push_back(id);
  const GlobalDescriptors descriptors =
      ComputeGlobalDescriptors(scene.database, ids, SmallVocabulary(), 2);
  int num_neighbours = 0;
  const Pairs pairs = MostSimilarPairs(descriptors, 1);
  for (const auto& [a, b] : pairs) {
    const uint32_t gap = std::min(b - a, 12 - (b - a));  // around the orbit
    num_neighbours += gap <= 2;
  }
  // Views 30 degrees apart share most of their points, views 60 apart fewer: every image's most
  // similar is within two steps.
  EXPECT_EQ(num_neighbours, static_cast<int>(pairs.size()));
}

}  // namespace
}  // namespace ramap
