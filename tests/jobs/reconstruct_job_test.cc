// The image-list jobs on rendered images of two textured walls: features into a new database
// (never over an existing one), its pairs matched in place, the whole reconstruction into one
// output folder, and a run that fails leaving nothing of itself behind.
#include "ramap/jobs/reconstruct_job.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// Five 320 x 240 views of two textured walls, z = 8 for x < 0 and z = 12 for x >= 0 (a step, so
// that the scene is not one plane), from centres (0.3 apart along x, alternately 0.1 up) each
// turned a little about y, through a pinhole camera with f 280: view1.png ... view5.png.
void RenderViews(const std::string& folder) {
  cv::Mat texture(1200, 2400, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 4.0);
  cv::normalize(texture, texture, 0, 255, cv::NORM_MINMAX);
  // The wall point (x, y) is texture pixel (100 x + 1200, 100 y + 600), read bilinearly.
  const auto sample = [&](const Eigen::Vector3d& point) {
    const double u = 100 * point.x() + 1200, v = 100 * point.y() + 600;
    const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
    const double a = u - u0, b = v - v0;
    return (1 - a) * (1 - b) * texture.at<uint8_t>(v0, u0) +
           a * (1 - b) * texture.at<uint8_t>(v0, u0 + 1) +
           (1 - a) * b * texture.at<uint8_t>(v0 + 1, u0) +
           a * b * texture.at<uint8_t>(v0 + 1, u0 + 1);
  };
  for (int view = 0; view < 5; ++view) {
    const Eigen::Vector3d centre(-0.6 + 0.3 * view, 0.1 * (view % 2), 0);
    const Eigen::Matrix3d world_from_cam =
        Eigen::AngleAxisd(0.02 * (view - 2), Eigen::Vector3d::UnitY()).toRotationMatrix();
    cv::Mat image(240, 320, CV_8UC1, cv::Scalar(0));
    for (int row = 0; row < 240; ++row) {
      for (int col = 0; col < 320; ++col) {
        const Eigen::Vector3d ray =
            world_from_cam * Eigen::Vector3d((col + 0.5 - 160) / 280, (row + 0.5 - 120) / 280, 1);
        // The near wall where the ray meets it at x < 0; else the far one where it meets it at
        // x >= 0; else neither (the step's shadow stays black).
        Eigen::Vector3d hit = centre + ray * (8 / ray.z());
        if (hit.x() >= 0) {
          hit = centre + ray * (12 / ray.z());
          if (hit.x() < 0) continue;
        }
        image.at<uint8_t>(row, col) = cv::saturate_cast<uint8_t>(sample(hit));
      }
    }
    cv::imwrite(folder + "/view" + std::to_string(view + 1) + ".png", image);
  }
}

// The rendered views, made once for every test of this file (removed at exit).
const std::string& Views() {
  static const test::TempDir dir;
  static const bool rendered = (RenderViews(dir.path()), true);
  (void)rendered;
  return dir.path();
}

FeatureOptions Calibrated() {
  FeatureOptions options;
  options.reader.camera_model = "PINHOLE";
  options.reader.camera_params = "280,280,160,120";
  options.reader.single_camera = true;
  options.extraction.max_num_features = 600;
  return options;
}

TEST(ReconstructJob, FeaturesIntoANewDatabaseOfTheGenerationAsked) {
  test::TempDir dir;
  FeatureOptions options = Calibrated();
  options.generation = DatabaseGeneration::kColmap4;
  std::ostringstream progress;
  EXPECT_EQ(
      ExtractFeaturesToDatabase(Views(), "", dir / "database.db", options, &progress, nullptr), 5u);
  const FeatureDatabase database = ReadColmapDatabase(dir / "database.db");
  EXPECT_EQ(database.generation, DatabaseGeneration::kColmap4);
  ASSERT_EQ(database.images.size(), 5u);
  EXPECT_EQ(database.images.at(1).name, "view1.png");
  ASSERT_EQ(database.cameras.size(), 1u);
  EXPECT_EQ(database.cameras.at(1).params, (std::vector<double>{280, 280, 160, 120}));
  for (const auto& [id, keypoints] : database.keypoints) EXPECT_GT(keypoints.size(), 100u);
  EXPECT_TRUE(database.two_view_geometries.empty());
  EXPECT_NE(progress.str().find("[ramap] features: 5 of 5 images (sift)"), std::string::npos)
      << progress.str();
  // Never over an existing database.
  const std::string before = test::ReadFileBytes(dir / "database.db");
  test::ExpectInputError(
      [&] {
        ExtractFeaturesToDatabase(Views(), "", dir / "database.db", options, nullptr, nullptr);
      },
      {"--database_path"});
  EXPECT_EQ(test::ReadFileBytes(dir / "database.db"), before);
}

TEST(ReconstructJob, MatchingADatabaseFileResolvesTheModeAndWritesTheMatches) {
  test::TempDir dir;
  ExtractFeaturesToDatabase(Views(), "", dir / "database.db", Calibrated(), nullptr, nullptr);
  const DatabaseMatchingSummary summary =
      MatchDatabaseFile(dir / "database.db", Calibrated(), nullptr);
  // Five images: auto matches them exhaustively, the 10 pairs screened first; neighbours and
  // next-but-one neighbours overlap by most of the image.
  EXPECT_EQ(summary.mode, MatchingMode::kExhaustive);
  EXPECT_EQ(summary.num_pairs_to_screen, 10);
  EXPECT_GE(summary.num_verified_pairs, 7);
  const FeatureDatabase database = ReadColmapDatabase(dir / "database.db");
  EXPECT_EQ(static_cast<int>(database.two_view_geometries.size()), summary.num_verified_pairs);
  const nlohmann::json json = MatchingSummaryToJson(summary);
  EXPECT_EQ(json["mode"], "exhaustive");
  EXPECT_EQ(json["pairs_verified"], summary.num_verified_pairs);
  EXPECT_EQ(json["pairs_to_screen"], 10);
}

TEST(ReconstructJob, ImagesToModelsInOneOutputFolder) {
  test::TempDir dir;
  ReconstructJob job;
  job.image_path = Views();
  job.output_path = dir / "out";
  job.options.features = Calibrated();
  job.options.mapper.num_threads = 2;
  const ReconstructResult result = RunReconstructJob(job, nullptr, nullptr);
  EXPECT_EQ(result.num_images, 5u);
  ASSERT_FALSE(result.mapping.reconstructions.empty());
  EXPECT_EQ(result.mapping.reconstructions[0].images.size(), 5u);
  EXPECT_TRUE(fs::exists(dir / "out/database.db"));
  const Reconstruction model = ReadColmapModel(dir / "out/sparse/0");
  EXPECT_EQ(model.images.size(), 5u);
  const nlohmann::json summary = test::ReadJsonFile(dir / "out/sparse/summary.json");
  EXPECT_EQ(summary["run"]["command"], "reconstruct");
  EXPECT_EQ(summary["run"]["feature_type"], "sift");
  EXPECT_EQ(summary["run"]["matching_mode"], "exhaustive");
  // The rendered centres are sqrt(0.3^2 + 0.1^2) apart from one view to the next: in the model,
  // up to its scale, every step as long as the first.
  std::vector<Eigen::Vector3d> centres;
  for (const auto& [id, image] : model.images)
    centres.push_back(CameraCenter(image.cam_from_world));
  const double step = (centres[1] - centres[0]).norm();
  for (size_t k = 2; k < centres.size(); ++k) {
    // Bundle-adjusted on SIFT of rendered images: within a few percent of a step.
    EXPECT_NEAR((centres[k] - centres[k - 1]).norm() / step, 1.0, 0.1) << "step " << k;
  }
}

TEST(ReconstructJob, AFailedRunLeavesNothingOfItself) {
  test::TempDir dir;
  fs::create_directories(dir / "images");
  std::ofstream(dir / "images/broken.png") << "not an image";
  ReconstructJob job;
  job.image_path = dir / "images";
  job.output_path = dir / "new";
  test::ExpectInputError([&] { RunReconstructJob(job, nullptr, nullptr); },
                         {dir / "images", "could be read"});
  EXPECT_FALSE(fs::exists(dir / "new"));
  // An existing output folder stays, with nothing of the run in it.
  fs::create_directories(dir / "existing");
  job.output_path = dir / "existing";
  EXPECT_THROW(RunReconstructJob(job, nullptr, nullptr), InputError);
  EXPECT_TRUE(fs::exists(dir / "existing"));
  EXPECT_TRUE(fs::is_empty(dir / "existing"));
}

}  // namespace
}  // namespace ramap
