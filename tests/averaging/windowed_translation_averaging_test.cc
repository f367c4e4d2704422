// AverageTranslationsInWindows on a noise-free synthetic drive: windows joined by their shared
// frames give the one trajectory one system gives, in the documented gauge, along the given order.
#include "ramap/averaging/windowed_translation_averaging.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "ramap/estimators/bearings.h"
#include "ramap/graph/tracks.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

// A noise-free 60-frame line with its true rotations, exact pair directions of every verified
// pair, the tracks of the verified matches and the keypoints' bearings.
struct Drive {
  SyntheticScene scene;
  std::vector<uint32_t> order;
  std::map<uint32_t, Eigen::Quaterniond> rotations;
  std::vector<PairDirection> directions;
  std::vector<Track> tracks;
  KeypointBearings bearings;
};

Drive MakeDrive() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 60);
  options.num_points = 1200;
  Drive drive{BuildSyntheticScene(options), {}, {}, {}, {}, {}};
  for (const auto& [id, image] : drive.scene.ground_truth.images) {
    drive.order.push_back(id);
    drive.rotations[id] = image.cam_from_world.rotation;
  }
  for (const auto& [pair_id, geometry] : drive.scene.database.two_view_geometries) {
    const Eigen::Vector3d c1 =
        CameraCenter(drive.scene.ground_truth.images.at(geometry.image_id1).cam_from_world);
    const Eigen::Vector3d c2 =
        CameraCenter(drive.scene.ground_truth.images.at(geometry.image_id2).cam_from_world);
    drive.directions.push_back({geometry.image_id1, geometry.image_id2, (c2 - c1).normalized()});
  }
  drive.tracks = BuildTracks(drive.scene.database.two_view_geometries);
  drive.bearings = ComputeBearings(drive.scene.database, "synthetic").bearings;
  return drive;
}

const Drive& SharedDrive() {
  static const Drive drive = MakeDrive();
  return drive;
}

// Windows of 20 frames sharing 8: [0, 28), [20, 48), [40, 60) of the 60 frames (a rest shorter
// than half a window joins the last one).
WindowedTranslationOptions ThreeWindows() {
  WindowedTranslationOptions windowed;
  windowed.window_frames = 20;
  windowed.overlap_frames = 8;
  return windowed;
}

// Largest distance between the centres of `result` and the true ones after the best similarity,
// over the extent of the true centres.
double RelativeCenterError(const Drive& drive, const TranslationAveragingResult& result) {
  Eigen::Matrix3Xd estimated(3, result.centers.size()), truth(3, result.centers.size());
  int k = 0;
  for (const auto& [id, center] : result.centers) {
    estimated.col(k) = center;
    truth.col(k++) = CameraCenter(drive.scene.ground_truth.images.at(id).cam_from_world);
  }
  const Eigen::Matrix4d sim = Eigen::umeyama(estimated, truth, true);
  const Eigen::Matrix3Xd aligned =
      (sim.topLeftCorner<3, 3>() * estimated).colwise() + sim.topRightCorner<3, 1>();
  const double extent = (truth.colwise() - truth.rowwise().mean()).colwise().norm().maxCoeff();
  return (aligned - truth).colwise().norm().maxCoeff() / extent;
}

// The mean over the pairs of both images' centres of the baseline projected on its direction.
double MeanProjectedBaseline(const std::vector<PairDirection>& directions,
                             const std::map<uint32_t, Eigen::Vector3d>& centers) {
  double sum = 0;
  int count = 0;
  for (const PairDirection& pair : directions) {
    if (!centers.count(pair.image_id1) || !centers.count(pair.image_id2)) continue;
    sum += pair.direction.dot(centers.at(pair.image_id2) - centers.at(pair.image_id1));
    ++count;
  }
  return sum / count;
}

// Keypoints are float32 (as in a COLMAP database): ~1e-5 px of rounding, which moves the exact
// solution by about 1e-6 of the drive's extent; 1e-5 leaves a margin.
constexpr double kExact = 1e-5;

TEST(WindowedTranslationAveraging, WindowsJoinedByTheirSharedFramesGiveOneTrajectory) {
  const Drive& drive = SharedDrive();
  const TranslationAveragingResult windows = AverageTranslationsInWindows(
      drive.order, drive.rotations, drive.directions, drive.tracks, drive.bearings,
      TranslationAveragingOptions(), ThreeWindows(), 2);
  EXPECT_EQ(windows.num_windows, 3);
  EXPECT_EQ(windows.centers.size(), 60u);
  EXPECT_TRUE(windows.unconstrained_images.empty());
  EXPECT_LT(RelativeCenterError(drive, windows), kExact);

  // One system on the same input gives the same centres in the same gauge.
  const TranslationAveragingResult one =
      AverageTranslations(drive.rotations, drive.directions, drive.tracks, drive.bearings,
                          TranslationAveragingOptions());
  EXPECT_EQ(one.num_windows, 0);
  const double extent = (one.centers.at(60) - one.centers.at(1)).norm();
  for (const auto& [id, center] : one.centers) {
    EXPECT_LT((windows.centers.at(id) - center).norm() / extent, kExact) << "image " << id;
  }
}

TEST(WindowedTranslationAveraging, GaugeIsTheFirstImageOfTheOrderAndAUnitMeanBaseline) {
  const Drive& drive = SharedDrive();
  const std::vector<uint32_t> reversed(drive.order.rbegin(), drive.order.rend());
  for (const std::vector<uint32_t>* order : {&drive.order, &reversed}) {
    const TranslationAveragingResult result = AverageTranslationsInWindows(
        *order, drive.rotations, drive.directions, drive.tracks, drive.bearings,
        TranslationAveragingOptions(), ThreeWindows(), 1);
    EXPECT_EQ(result.gauge_image_id, order->front());
    EXPECT_EQ(result.centers.at(order->front()), Eigen::Vector3d::Zero());
    // The gauge is set by this very mean: only rounding separates it from 1.
    EXPECT_NEAR(MeanProjectedBaseline(drive.directions, result.centers), 1.0, 1e-12);
  }
}

TEST(WindowedTranslationAveraging, ImagesWithoutARotationAreSkipped) {
  const Drive& drive = SharedDrive();
  std::map<uint32_t, Eigen::Quaterniond> rotations = drive.rotations;
  rotations.erase(1);  // the first frame: the gauge moves to the next
  rotations.erase(30);
  const TranslationAveragingResult result = AverageTranslationsInWindows(
      drive.order, rotations, drive.directions, drive.tracks, drive.bearings,
      TranslationAveragingOptions(), ThreeWindows(), 2);
  EXPECT_EQ(result.centers.size(), 58u);
  EXPECT_FALSE(result.centers.count(1));
  EXPECT_FALSE(result.centers.count(30));
  EXPECT_EQ(result.gauge_image_id, 2u);
  EXPECT_LT(RelativeCenterError(drive, result), kExact);
}

TEST(WindowedTranslationAveraging, NothingToJoinIsAStageFailure) {
  const Drive& drive = SharedDrive();
  // Without directions or tracks no window can place a camera, and no join is possible.
  EXPECT_THROW(AverageTranslationsInWindows(drive.order, drive.rotations, {}, {}, drive.bearings,
                                            TranslationAveragingOptions(), ThreeWindows(), 1),
               StageFailure);
}

TEST(WindowedTranslationAveraging, OverlapMustBeShorterThanTheWindow) {
  WindowedTranslationOptions windowed = ThreeWindows();
  windowed.overlap_frames = windowed.window_frames;
  test::ExpectInputError([&] { windowed.Check(); },
                         {"--TranslationAveraging.window_overlap_frames"});
  const Drive& drive = SharedDrive();
  test::ExpectInputError(
      [&] {
        AverageTranslationsInWindows(drive.order, drive.rotations, drive.directions, drive.tracks,
                                     drive.bearings, TranslationAveragingOptions(), windowed, 1);
      },
      {"--TranslationAveraging.window_overlap_frames"});
}

}  // namespace
}  // namespace ramap
