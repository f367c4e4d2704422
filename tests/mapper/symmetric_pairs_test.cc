// A landmark seen from every side whose back looks like its front: pairs between views from
// opposite sides verify, consistently, with the second view turned 180 degrees about the landmark
// (synthetic/synthetic_scene.h, aliased_symmetric). They must not fold the model onto one side:
// rotation averaging's pruning and the direction checks keep the consistent part of the graph.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ramap/eval/pose_metrics.h"
#include "ramap/mapper/mapper.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// `layout` around an object with 0.5 px noise, 10% wrong matches, and symmetric pairs at
// `ratio` of the true ones, each with as many matches as a good true pair has.
SyntheticScene SymmetricLandmark(SyntheticLayout layout, int num_images, double ratio,
                                 uint64_t seed) {
  SyntheticSceneOptions options;
  options.layout = layout;
  options.path = SyntheticPath::kCircle;
  options.num_images = num_images;
  options.num_points = 3000;
  options.overlap = 3;
  options.pixel_noise_sigma = 0.5;
  options.outlier_ratio = 0.1;
  options.aliased_symmetric = true;
  options.aliased_matches_on_tracks = true;
  options.aliased_pair_ratio = ratio;
  options.num_aliased_pair_matches = 200;
  options.seed = seed;
  return BuildSyntheticScene(options);
}

struct Folding {
  PoseEvaluation evaluation;
  size_t num_models = 0;
};

Folding MapAndEvaluate(const SyntheticScene& scene, const MapperOptions& options) {
  const MapperResult result = RunMapper(scene.database, options, "synthetic");
  Folding folding;
  folding.num_models = result.reconstructions.size();
  if (!result.reconstructions.empty())
    folding.evaluation = test::EvaluateAgainstTruth(result.reconstructions.front(), scene);
  return folding;
}

// A folded model puts the far side's cameras onto the near side: their rotations are then about
// 180 degrees off. Not one camera may be folded, and the rest stays as exact as the noise allows.
void ExpectNotFolded(const SyntheticScene& scene, const MapperOptions& options, int num_images) {
  ASSERT_GE(scene.aliased_pair_ids.size(), 8u);
  const Folding folding = MapAndEvaluate(scene, options);
  ASSERT_GE(folding.num_models, 1u);
  EXPECT_EQ(folding.evaluation.num_registered, num_images);
  EXPECT_LT(folding.evaluation.rotation_error_max_deg, 2.0);
  EXPECT_LT(folding.evaluation.relative_rotation_error_median_deg, 0.2);
  EXPECT_LT(folding.evaluation.ate_rmse_over_extent, 0.01);
}

// Without the fold check (rotation_folds.h) the same orbit folds: unweighted L1 averaging cuts the
// ring's few pairs at two seams rather than the many symmetric ones.
TEST(SymmetricPairs, AnOrbitWithSymmetricPairsIsNotFolded) {
  for (const uint64_t seed : {1, 2}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SyntheticScene scene = SymmetricLandmark(SyntheticLayout::kSequential, 48, 0.15, seed);
    ExpectNotFolded(scene, test::AveragingOnly(), 48);
    ExpectNotFolded(scene, MapperOptions(), 48);
    MapperOptions unchecked = test::AveragingOnly();
    unchecked.rotation_fold_check = false;
    EXPECT_GT(MapAndEvaluate(scene, unchecked).evaluation.rotation_error_max_deg, 90.0);
  }
}

// Photos from all around, as a collection has them: every pair that shares enough points is
// matched, and a tenth as many again are symmetric.
TEST(SymmetricPairs, PhotosFromAllAroundWithSymmetricPairsAreNotFolded) {
  for (const uint64_t seed : {1, 2}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const SyntheticScene scene = SymmetricLandmark(SyntheticLayout::kUnordered, 60, 0.1, seed);
    ExpectNotFolded(scene, test::AveragingOnly(), 60);
  }
}

}  // namespace
}  // namespace ramap
