// Prior alignment on synthetic scenes with known truth: the robust fit and its outlier report, the
// mapper's model aligned to its priors (metric, in the priors' frame) with priors in translation
// averaging and in bundle adjustment, and priors that cannot align a model.
#include "ramap/estimators/prior_alignment.h"

#include <gtest/gtest.h>

#include <random>

#include "ramap/eval/pose_metrics.h"
#include "ramap/mapper/mapper.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

std::map<uint32_t, Eigen::Vector3d> Centers(const Reconstruction& reconstruction) {
  std::map<uint32_t, Eigen::Vector3d> centers;
  for (const auto& [id, image] : reconstruction.images)
    centers[id] = CameraCenter(image.cam_from_world);
  return centers;
}

// Priors at the true centres plus Gaussian noise; `outliers` moved by 30 m.
PosePriors NoisyPriors(const Reconstruction& truth, double noise_m,
                       const std::set<uint32_t>& outliers, uint64_t seed = 3) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  PosePriors priors;
  for (const auto& [id, center] : Centers(truth)) {
    PosePrior prior;
    prior.center = center + Eigen::Vector3d(noise(random), noise(random), noise(random));
    if (outliers.count(id)) prior.center += Eigen::Vector3d(30, -20, 5);
    prior.std_dev_m = Eigen::Vector3d::Constant(std::max(noise_m, 0.05));
    priors.by_image[id] = prior;
  }
  return priors;
}

SyntheticScene LoopScene() {
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kLoop;
  options.num_images = 60;
  options.num_points = 1500;
  options.seed = 4;
  return BuildSyntheticScene(options);
}

double CenterRmse(const Reconstruction& estimate, const Reconstruction& truth) {
  double sum = 0.0;
  for (const auto& [id, image] : estimate.images) {
    sum += (CameraCenter(image.cam_from_world) - CameraCenter(truth.images.at(id).cam_from_world))
               .squaredNorm();
  }
  return std::sqrt(sum / estimate.images.size());
}

TEST(PriorAlignment, RobustFitFindsTheSimilarityAndReportsTheOutliers) {
  const SyntheticScene scene = LoopScene();
  // The "model": the truth under an unknown similarity.
  const Sim3d model_from_truth(
      0.2, Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d(5, -1, 2));
  std::map<uint32_t, Eigen::Vector3d> centers;
  for (const auto& [id, center] : Centers(scene.ground_truth))
    centers[id] = model_from_truth * center;
  const PosePriors priors = NoisyPriors(scene.ground_truth, 0.0, {7, 31});
  const PriorAlignment alignment = AlignCentersToPriors(centers, priors, PriorAlignmentOptions());
  ASSERT_TRUE(alignment.summary.aligned) << alignment.summary.problem;
  EXPECT_EQ(alignment.summary.num_priors, 60);
  EXPECT_EQ(alignment.summary.num_inliers, 58);
  ASSERT_EQ(alignment.summary.outliers.size(), 2u);
  EXPECT_EQ(
      std::min(alignment.summary.outliers[0].image_id, alignment.summary.outliers[1].image_id), 7u);
  EXPECT_NEAR(alignment.summary.outliers[0].error_m, std::sqrt(30 * 30 + 20 * 20 + 5 * 5), 1e-6);
  EXPECT_NEAR(alignment.summary.scale, 5.0, 1e-9);
  EXPECT_LT(alignment.summary.rmse_m, 1e-9);
  EXPECT_EQ(alignment.inliers.size(), 58u);
  // Default threshold: 3 x the 3D deviation of the priors (0.05 m per axis here).
  EXPECT_NEAR(alignment.summary.threshold_m, 3 * 0.05 * std::sqrt(3.0), 1e-12);
  // The inlier priors mapped back into the model frame are the model's centres.
  for (const PosePriorInModel& prior : PriorsInModelFrame(alignment)) {
    EXPECT_LT((prior.center - centers.at(prior.image_id)).norm(), 1e-9);
  }
}

TEST(PriorAlignment, PriorsThatCannotFixAFrameSayWhy) {
  const SyntheticScene scene = LoopScene();
  const std::map<uint32_t, Eigen::Vector3d> centers = Centers(scene.ground_truth);
  PosePriors identical;
  for (const auto& [id, center] : centers)
    identical.by_image[id] = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d::Ones()};
  const PriorAlignment same = AlignCentersToPriors(centers, identical, PriorAlignmentOptions());
  EXPECT_FALSE(same.summary.aligned);
  EXPECT_NE(same.summary.problem.find("coincide"), std::string::npos) << same.summary.problem;

  PosePriors on_a_line;
  for (const auto& [id, center] : centers)
    on_a_line.by_image[id] = {Eigen::Vector3d(id, 0, 0), Eigen::Vector3d::Ones()};
  const PriorAlignment line = AlignCentersToPriors(centers, on_a_line, PriorAlignmentOptions());
  EXPECT_FALSE(line.summary.aligned);
  EXPECT_FALSE(line.summary.problem.empty());

  // A scene a tenth of a metre across tagged by a 1 m GPS: the fit would be noise.
  PosePriors tiny;
  for (const auto& [id, center] : centers) {
    tiny.by_image[id] = {0.01 * center, Eigen::Vector3d::Ones()};
  }
  const PriorAlignment noise = AlignCentersToPriors(centers, tiny, PriorAlignmentOptions());
  EXPECT_FALSE(noise.summary.aligned);
  EXPECT_NE(noise.summary.problem.find("the priors spread over"), std::string::npos)
      << noise.summary.problem;

  PosePriors few;
  for (uint32_t id = 1; id <= 3; ++id) few.by_image[id] = {centers.at(id), Eigen::Vector3d::Ones()};
  few.by_image[999] = {Eigen::Vector3d::Zero(),
                       Eigen::Vector3d::Ones()};  // an image not in the model
  const PriorAlignment too_few = AlignCentersToPriors(centers, few, PriorAlignmentOptions());
  EXPECT_FALSE(too_few.summary.aligned);
  EXPECT_EQ(too_few.summary.num_priors, 3);
  EXPECT_NE(too_few.summary.problem.find("4 needed"), std::string::npos) << too_few.summary.problem;
}

// Noise-free priors in translation averaging put the cameras exactly on them.
TEST(PriorAlignment, TranslationAveragingWithExactPriorsLandsOnThem) {
  const SyntheticScene scene = LoopScene();
  std::map<uint32_t, Eigen::Quaterniond> rotations;
  for (const auto& [id, image] : scene.ground_truth.images)
    rotations[id] = image.cam_from_world.rotation;
  std::vector<PairDirection> directions;
  const std::map<uint32_t, Eigen::Vector3d> centers = Centers(scene.ground_truth);
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    directions.push_back(
        {geometry.image_id1, geometry.image_id2,
         (centers.at(geometry.image_id2) - centers.at(geometry.image_id1)).normalized()});
  }
  std::vector<PosePriorInModel> priors;
  for (const auto& [id, center] : centers) {
    if (id % 3 == 0) priors.push_back({id, center, Eigen::Matrix3d::Identity() / 0.5});
  }
  const TranslationAveragingResult result =
      AverageTranslations(rotations, directions, {}, {}, TranslationAveragingOptions(), priors);
  EXPECT_EQ(result.num_priors_used, 20);
  ASSERT_EQ(result.centers.size(), 60u);
  for (const auto& [id, center] : result.centers)
    EXPECT_LT((center - centers.at(id)).norm(), 1e-4) << id;
}

struct MapperCase {
  bool refine;  // false: averaging alone (no BA of any kind)
  bool priors_in_translation_averaging;
};

class AlignedMapper : public ::testing::TestWithParam<MapperCase> {};

// The mapper's model is in the priors' frame and metres: its centres match the truth without
// any alignment, to well below the 0.3 m noise of the priors, and the two wrong fixes are named.
TEST_P(AlignedMapper, ModelInThePriorsFrameWithOutliersReported) {
  const SyntheticScene scene = LoopScene();
  const PosePriors priors = NoisyPriors(scene.ground_truth, 0.3, {12, 40});
  MapperOptions options;
  options.refine = GetParam().refine;
  options.subset_adjustment = GetParam().refine;
  options.prior_alignment.use_in_translation_averaging = GetParam().priors_in_translation_averaging;
  const MapperResult result = RunMapper(scene.database, options, "synthetic", nullptr, priors);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const PriorAlignmentSummary& geo = result.summary.components.front().prior_alignment;
  ASSERT_TRUE(geo.aligned) << geo.problem;
  EXPECT_EQ(geo.used_in_translation_averaging, GetParam().priors_in_translation_averaging);
  EXPECT_EQ(geo.used_in_bundle_adjustment, GetParam().refine);
  EXPECT_EQ(geo.num_inliers, 58);
  ASSERT_EQ(result.summary.prior_outliers.size(), 2u);
  std::set<std::string> named;
  for (const DroppedItem& item : result.summary.prior_outliers) named.insert(item.what);
  EXPECT_EQ(named, (std::set<std::string>{scene.ground_truth.images.at(12).name,
                                          scene.ground_truth.images.at(40).name}));
  EXPECT_NEAR(geo.rmse_m, 0.3 * std::sqrt(3.0), 0.15);  // the noise of the priors
  const double rmse = CenterRmse(result.reconstructions.front(), scene.ground_truth);
  std::printf("centre error without alignment: %.3f m (priors: 0.3 m per axis)\n", rmse);
  EXPECT_LT(rmse, 0.15);
  // Points were triangulated in the same frame: every one in front of its cameras.
  const Reconstruction& model = result.reconstructions.front();
  for (const auto& [point_id, point] : model.points3D) {
    for (const TrackElement& element : point.track) {
      ASSERT_GT((model.images.at(element.image_id).cam_from_world * point.xyz).z(), 0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Uses, AlignedMapper,
                         ::testing::Values(MapperCase{false, true}, MapperCase{false, false},
                                           MapperCase{true, true}));

// The refit with priors is a second translation averaging: an image that only pure rotations
// link to the rest (test::StandstillLineScene's image 11, here without a prior of its own) must
// again be placed with its neighbours, in the priors' frame, not dropped.
TEST(AlignedMapper, AFrameStandingStillIsPlacedAfterTheRefitWithPriors) {
  const SyntheticScene scene = test::StandstillLineScene();
  PosePriors priors = NoisyPriors(scene.ground_truth, 0.0, {});
  priors.by_image.erase(11);
  MapperOptions options = test::AveragingOnly();
  options.prior_alignment.use_in_translation_averaging = true;
  const MapperResult result = RunMapper(scene.database, options, "synthetic", nullptr, priors);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const PriorAlignmentSummary& geo = result.summary.components.front().prior_alignment;
  ASSERT_TRUE(geo.aligned) << geo.problem;
  EXPECT_TRUE(geo.used_in_translation_averaging);
  const Reconstruction& model = result.reconstructions.front();
  EXPECT_EQ(model.images.size(), 30u);
  ASSERT_TRUE(model.images.count(11));
  const Eigen::Vector3d truth = CameraCenter(scene.ground_truth.images.at(11).cam_from_world);
  EXPECT_LT((CameraCenter(model.images.at(11).cam_from_world) - truth).norm(), 1e-3);
}

TEST(AlignedMapper, PriorsThatCannotAlignLeaveTheModelAsWithout) {
  const SyntheticScene scene = LoopScene();
  PosePriors identical;
  for (const auto& [id, image] : scene.ground_truth.images)
    identical.by_image[id] = {Eigen::Vector3d(4, 4, 4), Eigen::Vector3d::Ones()};
  const MapperResult with =
      RunMapper(scene.database, test::AveragingOnly(), "synthetic", nullptr, identical);
  const MapperResult without = RunMapper(scene.database, test::AveragingOnly(), "synthetic");
  ASSERT_EQ(with.reconstructions.size(), 1u);
  EXPECT_FALSE(with.summary.components.front().prior_alignment.aligned);
  EXPECT_NE(with.summary.components.front().prior_alignment.problem.find("coincide"),
            std::string::npos);
  EXPECT_FALSE(with.geodetic_origin.has_value());
  EXPECT_LT(CenterRmse(with.reconstructions.front(), without.reconstructions.front()), 1e-12);
}

}  // namespace
}  // namespace ramap
