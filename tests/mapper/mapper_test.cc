// The mapper end to end on synthetic scenes: exact recovery without noise (sequences, forward
// motion, orbits, unordered collections), several connected components, and unusable input.
#include "ramap/mapper/mapper.h"

#include <gtest/gtest.h>

#include "ramap/eval/pose_metrics.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

PoseEvaluation MapAndEvaluate(const SyntheticScene& scene, MapperResult* result_out = nullptr,
                              const MapperOptions& options = test::AveragingOnly()) {
  const MapperResult result = RunMapper(scene.database, options, "synthetic");
  EXPECT_FALSE(result.reconstructions.empty());
  const PoseEvaluation evaluation =
      test::EvaluateAgainstTruth(result.reconstructions.front(), scene);
  if (result_out != nullptr) *result_out = result;
  return evaluation;
}

struct ExactCase {
  const char* name;
  SyntheticSceneOptions options;
};

// ctest lists a case by its name, not by a dump of its bytes.
void PrintTo(const ExactCase& scene, std::ostream* out) { *out << scene.name; }

class MapperExactRecovery : public ::testing::TestWithParam<ExactCase> {};

// Keypoints are float32 (as in a COLMAP database): ~1e-5 px rounding bounds what exact can mean.
TEST_P(MapperExactRecovery, EveryImageAndPoseWithoutNoise) {
  const SyntheticScene scene = BuildSyntheticScene(GetParam().options);
  MapperResult result;
  const PoseEvaluation evaluation = MapAndEvaluate(scene, &result);
  EXPECT_EQ(evaluation.num_registered, GetParam().options.num_images);
  EXPECT_EQ(result.reconstructions.size(), 1u);
  EXPECT_LT(evaluation.relative_rotation_error_median_deg, 1e-4);
  EXPECT_LT(evaluation.rotation_error_max_deg, 1e-3);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-5);
  EXPECT_GT(result.summary.components.front().num_points, 1000);
  EXPECT_LT(result.summary.components.front().mean_reprojection_error_px, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, MapperExactRecovery,
    ::testing::Values(
        ExactCase{"forward_line",
                  test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 30)},
        ExactCase{"loop", test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLoop, 60)},
        ExactCase{"orbit",
                  test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kCircle, 24)},
        ExactCase{"unordered",
                  test::NoiseFree(SyntheticLayout::kUnordered, SyntheticPath::kLine, 20)}),
    [](const ::testing::TestParamInfo<ExactCase>& info) { return info.param.name; });

// A 60-frame loop with 0.5 px of noise, 10% wrong matches and 5 outlier pairs.
SyntheticScene NoisyLoop() {
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kLoop;
  options.num_images = 60;
  options.num_points = 2000;
  options.pixel_noise_sigma = 0.5;
  options.outlier_ratio = 0.1;
  options.num_outlier_pairs = 5;
  options.seed = 4;
  return BuildSyntheticScene(options);
}

TEST(Mapper, NoisySequenceWithWrongMatchesAndOutlierPairs) {
  const SyntheticScene scene = NoisyLoop();
  const PoseEvaluation evaluation = MapAndEvaluate(scene);
  EXPECT_EQ(evaluation.num_registered, 60);
  EXPECT_LT(evaluation.relative_rotation_error_median_deg, 0.1);
  EXPECT_LT(evaluation.ate_rmse_over_path_length, 0.01);
}

// A facade's repeat matched a few frames away: pairs whose matches obey the true rotation but a
// second camera 3 m off, joining the points' tracks. Rotation averaging cannot see them; the
// cycle check of the pair directions rejects them, names each in summary.json's dropped edges
// with its reason, and the model stays as exact as the noise allows. Without the checks (and
// translation averaging's row rejection) the same drive is bent.
TEST(Mapper, PairsAliasedInTranslationAreRejectedWithTheirReasons) {
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kLoop;
  options.num_images = 60;
  options.num_points = 3000;
  options.pixel_noise_sigma = 0.5;
  options.num_aliased_pair_matches = 300;
  options.seed = 11;
  const SyntheticScene scene = BuildSyntheticScene(test::WithFacadeRepeats(options, 6, 3.0));
  ASSERT_EQ(scene.aliased_pair_ids.size(), 6u);
  MapperResult result;
  const PoseEvaluation checked = MapAndEvaluate(scene, &result);
  int named = 0;
  for (const uint64_t pair_id : scene.aliased_pair_ids) {
    const auto [image_id1, image_id2] = PairIdToImagePair(pair_id);
    const std::string what =
        scene.database.images.at(image_id1).name + " " + scene.database.images.at(image_id2).name;
    for (const DroppedItem& dropped : result.summary.dropped_edges) {
      if (dropped.what == what &&
          dropped.reason.rfind("pair direction off its cycles by ", 0) == 0) {
        ++named;
      }
    }
  }
  EXPECT_GE(named, 5);
  EXPECT_EQ(checked.num_registered, 60);
  MapperOptions unchecked = test::AveragingOnly();
  unchecked.direction_consistency.mode = DirectionCheckMode::kOff;
  unchecked.translation_averaging.max_rejection_rounds = 0;
  const PoseEvaluation bent = MapAndEvaluate(scene, nullptr, unchecked);
  EXPECT_LT(checked.ate_rmse_over_path_length, 0.005);
  EXPECT_GT(bent.ate_rmse_over_path_length, 2 * checked.ate_rmse_over_path_length);
}

// A car waiting at a light (test::StandstillLineScene): frame 11 has no direction to any camera,
// yet it stands where frames 10 and 12 stand.
TEST(Mapper, AFrameLinkedOnlyByPureRotationsStandsWithItsNeighbours) {
  const SyntheticScene scene = test::StandstillLineScene();
  MapperResult result;
  const PoseEvaluation evaluation = MapAndEvaluate(scene, &result);
  EXPECT_EQ(evaluation.num_registered, 30);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-4);
}

// Averaging options that solve translation averaging of any sequence in windows of
// `window_frames` frames sharing `overlap_frames` (windowed_translation_averaging.h).
MapperOptions InWindows(int window_frames, int overlap_frames) {
  MapperOptions options = test::AveragingOnly();
  options.translation_windows.min_num_images = 2;
  options.translation_windows.window_frames = window_frames;
  options.translation_windows.overlap_frames = overlap_frames;
  return options;
}

// The 60-frame loop in six windows joined by their shared frames and the loop's pairs: as exact as
// in one system.
TEST(Mapper, TranslationsInWindowsAreExactWithoutNoise) {
  const SyntheticScene scene =
      BuildSyntheticScene(test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLoop, 60));
  MapperResult result;
  const PoseEvaluation evaluation = MapAndEvaluate(scene, &result, InWindows(10, 4));
  EXPECT_EQ(evaluation.num_registered, 60);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-5);
  EXPECT_EQ(result.summary.components.front().num_translation_windows, 6);
}

// Noise, wrong matches and outlier pairs, in windows of 10: within the bound of the one-system
// test above (NoisySequenceWithWrongMatchesAndOutlierPairs).
TEST(Mapper, TranslationsInWindowsOfANoisySequence) {
  const SyntheticScene scene = NoisyLoop();
  const PoseEvaluation evaluation = MapAndEvaluate(scene, nullptr, InWindows(10, 4));
  EXPECT_EQ(evaluation.num_registered, 60);
  EXPECT_LT(evaluation.ate_rmse_over_path_length, 0.01);
}

// Windows of 7 frames every 5: those of frames 6-12 and 11-17 share only frames 11 and 12, and
// frame 11 has no position of its own (it stands with 10 and 12). They are merged, with a window
// of context on either side, into frames 1-22, and solved again (six windows -> three); frame 11
// still stands where its neighbours stand.
TEST(Mapper, WindowsTiedByAStandstillAreMerged) {
  const SyntheticScene scene = test::StandstillLineScene();
  MapperResult result;
  const PoseEvaluation evaluation = MapAndEvaluate(scene, &result, InWindows(5, 2));
  EXPECT_EQ(evaluation.num_registered, 30);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-4);
  EXPECT_EQ(result.summary.components.front().num_translation_windows, 3);
}

// Two sequences that share no verified pair: two models, largest first, both complete.
TEST(Mapper, EveryConnectedComponentIsReconstructed) {
  SyntheticScene scene =
      BuildSyntheticScene(test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 30));
  for (auto it = scene.database.two_view_geometries.begin();
       it != scene.database.two_view_geometries.end();) {
    const bool crosses = (it->second.image_id1 <= 18) != (it->second.image_id2 <= 18);
    it = crosses ? scene.database.two_view_geometries.erase(it) : std::next(it);
  }
  const MapperResult result = RunMapper(scene.database, test::AveragingOnly(), "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 2u);
  EXPECT_EQ(result.reconstructions[0].images.size(), 18u);
  EXPECT_EQ(result.reconstructions[1].images.size(), 12u);
  EXPECT_EQ(result.summary.num_registered_images, 30);
  EXPECT_TRUE(result.summary.dropped_images.empty());
}

// The mapper refuses `database` with an InputError naming it ("db.sqlite") and `message`.
void ExpectMapperRefuses(const FeatureDatabase& database, const std::string& message) {
  test::ExpectInputError([&] { RunMapper(database, MapperOptions(), "db.sqlite"); },
                         {"db.sqlite", message});
}

TEST(Mapper, UnusableDatabasesAreClearErrors) {
  const SyntheticScene scene =
      BuildSyntheticScene(test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 10));
  FeatureDatabase no_geometries = scene.database;
  no_geometries.two_view_geometries.clear();
  ExpectMapperRefuses(no_geometries, "no image pair has verified matches");

  FeatureDatabase single = scene.database;
  single.images.erase(std::next(single.images.begin()), single.images.end());
  single.two_view_geometries.clear();
  ExpectMapperRefuses(single, "no image pair has verified matches");

  FeatureDatabase empty = scene.database;
  empty.images.clear();
  ExpectMapperRefuses(empty, "the database has no images");

  // Every verified pair's inliers paired at random: no relative pose survives.
  FeatureDatabase outliers = scene.database;
  uint32_t shift = 1;
  for (auto& [pair_id, geometry] : outliers.two_view_geometries) {
    const size_t n = geometry.inlier_matches.size();
    for (size_t k = 0; k < n; ++k) {
      geometry.inlier_matches[k].point2D_idx2 = scene.database.two_view_geometries.at(pair_id)
                                                    .inlier_matches[(k * 7 + shift) % n]
                                                    .point2D_idx2;
    }
    ++shift;
  }
  ExpectMapperRefuses(outliers, "rejected");
}

}  // namespace
}  // namespace ramap
