// Prior alignment on real images: KITTI 07's first 160 frames, its ground truth turned into WGS84
// GPS fixes about Karlsruhe with GeographicLib (2 m noise per axis, five gross errors, one fix on
// the other side of the planet, ten frames without a fix) and stored as the database's priors,
// as COLMAP stores EXIF GPS. The mapper's model must come out in metres in the local ENU frame.
#include <gtest/gtest.h>

#include <random>

#include "ramap/features/image_reader.h"
#include "ramap/features/matching_plan.h"
#include "ramap/geometry/alignment.h"
#include "ramap/geometry/geodetic.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/trajectory.h"
#include "ramap/jobs/pose_priors.h"
#include "ramap/mapper/mapper.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(PriorAlignmentRealData, Kitti07FromNoisyGpsToMetricModel) {
  RAMAP_REQUIRE_SHARED_DATA(folder, "kitti_3dv_tutorial/kitti07_first160");
  std::vector<std::string> names;
  for (int k = 0; k < 160; ++k) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.png", k);
    names.push_back(name);
  }
  ImageReaderOptions reader;
  reader.camera_model = "PINHOLE";
  reader.camera_params = "707.0912,707.0912,601.8873,183.1104";
  reader.single_camera = true;
  FeatureExtractionOptions extraction;
  extraction.type = FeatureType::kOrb;  // ORB and 2000 features keep the test short
  extraction.max_num_features = 2000;
  ExtractionSummary extracted;
  FeatureDatabase database =
      ExtractImageFeatures(folder + "/image_0", names, reader, extraction, &extracted);
  ASSERT_EQ(extracted.num_images, 160);
  FeatureMatchingOptions matching;
  matching.mode = MatchingMode::kSequential;
  matching.overlap = 5;
  MatchDatabase(&database, matching);

  // Ground truth (KITTI: x right, y down, z forward of the first camera) as east, north, up.
  const std::map<std::string, Rigid3d> truth = GroundTruthByImageName(
      ReadGroundTruth(folder + "/poses_gt.txt", GroundTruthFormat::kKitti), names);
  const LocalEnuFrame karlsruhe({49.0113, 8.4165, 115.0});
  std::map<std::string, Eigen::Vector3d> true_enu;
  for (const auto& [name, pose] : truth) {
    const Eigen::Vector3d c = CameraCenter(pose);
    true_enu[name] = Eigen::Vector3d(c.x(), c.z(), -c.y());
  }
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, 2.0);
  const std::set<int> gross = {15, 45, 80, 110, 140};
  std::set<std::string> gross_names;
  for (auto& [id, image] : database.images) {
    const int frame = std::stoi(image.name.substr(0, 6));
    if (frame >= 60 && frame < 70) continue;  // no fix
    Eigen::Vector3d enu =
        true_enu.at(image.name) + Eigen::Vector3d(noise(random), noise(random), noise(random));
    if (gross.count(frame)) {
      enu += Eigen::Vector3d(60, -40, 10);
      gross_names.insert(image.name);
    }
    GeodeticPoint fix = karlsruhe.ToGeodetic(enu);
    if (frame == 100) fix = {-fix.latitude_deg, fix.longitude_deg - 180, fix.altitude_m};
    image.prior_translation = Eigen::Vector3d(fix.latitude_deg, fix.longitude_deg, fix.altitude_m);
  }
  test::TempDir dir;
  WriteColmapDatabase(database, dir / "database.db");
  database = ReadColmapDatabase(dir / "database.db");

  PosePriorOptions prior_options;
  prior_options.std_dev_m = Eigen::Vector3d(2, 2, 2);
  const LocalizedPriors priors =
      LocalizePriors(PriorRecordsFromDatabase(database), database, prior_options);
  EXPECT_EQ(priors.num_records, 150);
  EXPECT_EQ(priors.priors.by_image.size(), 149u);
  ASSERT_EQ(priors.warnings.size(), 1u);
  EXPECT_NE(priors.warnings[0].find("prior of 000100.png not used"), std::string::npos)
      << priors.warnings[0];

  const MapperResult result =
      RunMapper(database, test::AveragingOnly(), "kitti07", nullptr, priors.priors);
  ASSERT_FALSE(result.reconstructions.empty());
  const Reconstruction& model = result.reconstructions.front();
  EXPECT_EQ(model.images.size(), 160u);
  const PriorAlignmentSummary& geo = result.summary.components.front().prior_alignment;
  ASSERT_TRUE(geo.aligned) << geo.problem;
  ASSERT_TRUE(result.geodetic_origin.has_value());
  std::set<std::string> reported;
  for (const DroppedItem& item : result.summary.prior_outliers) reported.insert(item.what);
  EXPECT_EQ(reported, gross_names);

  // The truth in the model's frame (ENU about its own origin, the median fix), through WGS84.
  const LocalEnuFrame model_frame(*result.geodetic_origin);
  std::vector<Eigen::Vector3d> estimated, expected;
  double sum_squares = 0.0;
  for (const auto& [id, image] : model.images) {
    estimated.push_back(CameraCenter(image.cam_from_world));
    expected.push_back(model_frame.FromGeodetic(karlsruhe.ToGeodetic(true_enu.at(image.name))));
    sum_squares += (estimated.back() - expected.back()).squaredNorm();
  }
  const double absolute_rmse = std::sqrt(sum_squares / estimated.size());
  AlignmentOptions rigid;
  rigid.estimate_scale = false;
  const AlignmentResult alignment = AlignPoints(estimated, expected, rigid);
  ASSERT_TRUE(alignment.ok());
  double ate = 0.0;
  for (size_t k = 0; k < estimated.size(); ++k) {
    ate += (alignment.target_from_source * estimated[k] - expected[k]).squaredNorm();
  }
  ate = std::sqrt(ate / estimated.size());
  std::printf(
      "KITTI 07 aligned to its priors: %d of %d priors, %zu outliers; centre RMSE %.2f m as "
      "written, metric ATE (rigid, no scale) %.2f m, GPS noise 3.46 m (3D)\n",
      geo.num_inliers, geo.num_priors, geo.outliers.size(), absolute_rmse, ate);
  EXPECT_LT(absolute_rmse, 2.0);
  EXPECT_LT(ate, 1.0);
}

}  // namespace
}  // namespace ramap
