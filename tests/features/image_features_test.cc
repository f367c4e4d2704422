// Image-list input: features of synthetic and real images, matching and verification on real
// images against ground truth, awkward folders, and a database that COLMAP's mapper accepts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ramap/features/feature_matching.h"
#include "ramap/features/image_reader.h"
#include "ramap/features/matching_plan.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"
#include "test_support.h"
#include "texture_image.h"

namespace ramap {
namespace {

TEST(ImageFeatures, OrbAndSiftOnATexture) {
  const cv::Mat image = test::BlurredNoise(640, 480, 1);
  for (const FeatureType type : {FeatureType::kOrb, FeatureType::kSift}) {
    FeatureExtractionOptions options;
    options.type = type;
    options.max_num_features = 1000;
    const ImageFeatures features = ExtractFeatures(image, options);
    SCOPED_TRACE(FeatureTypeName(type));
    EXPECT_GT(features.keypoints.size(), 200u);
    EXPECT_LE(features.keypoints.size(), 1100u);
    EXPECT_EQ(features.descriptors.size(), features.keypoints.size());
    EXPECT_EQ(features.descriptors.num_cols, type == FeatureType::kOrb ? 32 : 128);
    for (size_t k = 0; k < features.keypoints.size(); ++k) {
      const Eigen::Vector2d xy = features.keypoints.xy(k);
      ASSERT_TRUE(xy.x() >= 0 && xy.x() <= 640 && xy.y() >= 0 && xy.y() <= 480);
    }
  }
}

TEST(ImageFeatures, DownscaledDetectionKeepsFullResolutionCoordinates) {
  const cv::Mat image = test::BlurredNoise(1200, 800, 2);
  FeatureExtractionOptions options;
  options.max_image_size = 600;
  const ImageFeatures features = ExtractFeatures(image, options);
  double max_x = 0;
  for (size_t k = 0; k < features.keypoints.size(); ++k) {
    max_x = std::max(max_x, features.keypoints.xy(k).x());
  }
  EXPECT_GT(max_x, 1000);  // not in the 600-pixel image's coordinates
}

TEST(ImageFeatures, ShiftedCopyMatchesAtTheShift) {
  const cv::Mat image = test::BlurredNoise(640, 480, 3);
  const cv::Mat shifted = image(cv::Rect(20, 10, 600, 460)).clone();
  for (const FeatureType type : {FeatureType::kOrb, FeatureType::kSift}) {
    SCOPED_TRACE(FeatureTypeName(type));
    FeatureExtractionOptions options;
    options.type = type;
    const ImageFeatures a = ExtractFeatures(image, options), b = ExtractFeatures(shifted, options);
    std::vector<float> ratios;
    const std::vector<FeatureMatch> matches =
        MatchDescriptors(a.descriptors, b.descriptors, FeatureMatchingOptions(), &ratios);
    ASSERT_GT(matches.size(), 100u);
    ASSERT_EQ(ratios.size(), matches.size());
    int at_shift = 0;
    for (const FeatureMatch& m : matches) {
      const Eigen::Vector2d d = a.keypoints.xy(m.point2D_idx1) - b.keypoints.xy(m.point2D_idx2);
      at_shift += (d - Eigen::Vector2d(20, 10)).norm() < 1.5;
    }
    // Random texture repeats itself at small scales: most, not all, matches are right.
    EXPECT_GT(at_shift, 0.8 * matches.size());
  }
}

// Preemptive matching (exhaustive mode) matches in full only the pairs whose largest-scale
// features already agree: the image and its shifted copy, not the unrelated texture.
TEST(ImageFeatures, PreemptiveMatchingSkipsPairsThatShareNothing) {
  const cv::Mat image = test::BlurredNoise(640, 480, 3);
  FeatureDatabase database;
  database.cameras[1] = test::VgaPinholeCamera();
  const cv::Mat views[] = {image, image(cv::Rect(20, 10, 600, 460)).clone(),
                           test::BlurredNoise(640, 480, 9)};
  for (uint32_t id = 1; id <= 3; ++id) {
    Image entry;
    entry.image_id = id;
    entry.name = "view" + std::to_string(id) + ".png";
    entry.camera_id = 1;
    database.images[id] = entry;
    ImageFeatures features = ExtractFeatures(views[id - 1], FeatureExtractionOptions());
    database.keypoints[id] = std::move(features.keypoints);
    database.descriptors[id] = std::move(features.descriptors);
  }
  FeatureMatchingOptions matching;
  matching.mode = MatchingMode::kExhaustive;
  FeatureDatabase screened = database;
  const DatabaseMatchingSummary with = MatchDatabase(&screened, matching);
  EXPECT_EQ(with.num_pairs_to_screen, 3);
  EXPECT_EQ(with.num_pairs_kept_by_screening, 1);
  EXPECT_EQ(with.num_pairs, 1);
  EXPECT_TRUE(screened.matches.count(ImagePairToPairId(1, 2)));
  matching.preemptive_num_features = 0;
  const DatabaseMatchingSummary without = MatchDatabase(&database, matching);
  EXPECT_EQ(without.num_pairs, 3);
  EXPECT_EQ(without.num_pairs_kept_by_screening, 3);
}

TEST(ImageFeatures, AwkwardFolderIsReportedNotFatal) {
  test::TempDir dir;
  cv::imwrite(dir / "grey.png", test::BlurredNoise(320, 240, 4));
  cv::Mat colour;
  cv::cvtColor(test::BlurredNoise(400, 300, 5), colour, cv::COLOR_GRAY2BGR);
  cv::imwrite(dir / "colour.jpg", colour);
  std::ofstream(dir / "empty.jpg").close();
  std::ofstream(dir / "text.png") << "not an image";
  std::ofstream(dir / "notes.txt") << "ignored: not an image name";
  const std::vector<std::string> names = ListImages(dir.path(), "");
  EXPECT_EQ(names, (std::vector<std::string>{"colour.jpg", "empty.jpg", "grey.png", "text.png"}));
  ImageReaderOptions reader;
  reader.single_camera = true;
  ExtractionSummary summary;
  const FeatureDatabase database =
      ExtractImageFeatures(dir.path(), names, reader, FeatureExtractionOptions(), &summary);
  EXPECT_EQ(summary.num_images, 2);
  EXPECT_EQ(summary.skipped_images,
            (std::vector<std::string>{"empty.jpg: empty file",
                                      "text.png: not an image OpenCV can read"}));
  ASSERT_EQ(database.images.size(), 2u);
  EXPECT_EQ(database.cameras.size(), 2u);  // two sizes, so two cameras despite single_camera
  EXPECT_EQ(database.cameras.at(1).width, 400u);
  // SIMPLE_RADIAL guess: f = 1.2 * 400, principal point at the centre.
  EXPECT_EQ(database.cameras.at(1).params, (std::vector<double>{480, 200, 150, 0}));
  EXPECT_THROW(ListImages(dir / "missing", ""), InputError);
  ImageReaderOptions bad;
  bad.camera_model = "PINHOLE";
  bad.camera_params = "500,500,320";
  EXPECT_THROW(bad.Check(), InputError);
}

// Ten templeRing views (a 1520 px lens; views 20-29, where the lighting does not change): ORB
// features, exhaustive matching and verification; the verified relative rotations agree with the
// ground truth, and COLMAP's mapper reconstructs the database ramap wrote.
TEST(ImageFeatures, TempleRingDatabaseIsRightAndColmapMapsIt) {
  RAMAP_REQUIRE_SHARED_DATA(folder, "middlebury_templeRing");
  std::vector<std::string> names;
  for (int k = 20; k <= 29; ++k) names.push_back("templeR00" + std::to_string(k) + ".png");
  ImageReaderOptions reader;
  reader.camera_model = "PINHOLE";
  reader.camera_params = "1520.4,1525.9,302.32,246.87";
  reader.single_camera = true;
  ExtractionSummary summary;
  FeatureExtractionOptions extraction;
  extraction.max_num_features = 2000;  // keeps the test's matching short
  FeatureDatabase database = ExtractImageFeatures(folder, names, reader, extraction, &summary);
  ASSERT_EQ(summary.num_images, 10);
  FeatureMatchingOptions matching;
  matching.mode = MatchingMode::kExhaustive;
  const DatabaseMatchingSummary matched = MatchDatabase(&database, matching);
  EXPECT_EQ(matched.num_pairs_to_screen, 45);
  EXPECT_LE(matched.num_pairs, 45);  // those preemptive matching kept
  EXPECT_GE(matched.num_verified_pairs, 15);
  const std::map<std::string, Rigid3d> truth = GroundTruthByImageName(
      ReadGroundTruth(folder + "/templeR_par.txt", GroundTruthFormat::kMiddlebury), names);
  std::vector<double> errors;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    EXPECT_EQ(geometry.config, TwoViewConfig::kCalibrated);
    const Rigid3d expected = truth.at(database.images.at(geometry.image_id2).name) *
                             truth.at(database.images.at(geometry.image_id1).name).Inverse();
    errors.push_back(expected.rotation.angularDistance(geometry.cam2_from_cam1.rotation) * 180 /
                     M_PI);
  }
  // Every inlier keeps the descriptor ratio that let it through the ratio test.
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    ASSERT_EQ(geometry.inlier_ratios.size(), geometry.inlier_matches.size());
    for (const float ratio : geometry.inlier_ratios) {
      ASSERT_TRUE(ratio >= 0 && ratio < matching.max_ratio) << ratio;
    }
  }
  std::sort(errors.begin(), errors.end());
  std::printf("verified pairs: %zu, median rotation error of their poses: %.3f deg\n",
              errors.size(), errors[errors.size() / 2]);
  EXPECT_LT(errors[errors.size() / 2], 2.0);

  RAMAP_REQUIRE_COLMAP();
  test::TempDir dir;
  WriteColmapDatabase(database, dir / "database.db");
  std::filesystem::create_directories(dir / "sparse");
  const test::CommandResult mapper =
      test::RunCommand("colmap mapper --database_path '" + (dir / "database.db") +
                       "' --image_path '" + folder + "' --output_path '" + (dir / "sparse") +
                       "' --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
                       " --Mapper.ba_refine_extra_params 0 --Mapper.num_threads 2");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  EXPECT_EQ(ReadColmapModel(dir / "sparse/0").images.size(), 10u);
  // COLMAP read a database carrying ramap's ratio table, which also reads back.
  EXPECT_FALSE(ReadColmapDatabase(dir / "database.db")
                   .two_view_geometries.begin()
                   ->second.inlier_ratios.empty());
}

}  // namespace
}  // namespace ramap
