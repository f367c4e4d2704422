// Prior alignment as a user runs it: `ramap mapper --PosePrior.path` and `ramap model_aligner`
// write the model in ENU metres with its origin and a GeoJSON of the cameras; priors that cannot
// align end in a message (model_aligner: non-zero, nothing written; mapper: the model as
// without priors).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "exif_writer.h"
#include "ramap/geometry/geodetic.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/geo_export.h"
#include "ramap/io/pose_prior_file.h"
#include "ramap/io/trajectory.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

const GeodeticPoint kOrigin{46.5197, 6.5663, 400.0};  // Lausanne

// A synthetic loop and WGS84 priors at its true centres (world units taken as metres, z up).
Reconstruction SynthesizeWithPriors(const test::TempDir& dir, bool identical = false) {
  const test::CommandResult result = test::RunCommand(
      test::RamapCommand() + "synthesize --output_path '" + (dir / "scene") +
      "' --Synthetic.path loop --Synthetic.num_images 30 --Synthetic.num_points 800"
      " --Synthetic.seed 5");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const Reconstruction truth = ReadColmapModel(dir / "scene/ground_truth");
  const LocalEnuFrame frame(kOrigin);
  std::vector<PriorRecord> records;
  for (const auto& [id, image] : truth.images) {
    const GeodeticPoint fix =
        frame.ToGeodetic(identical ? Eigen::Vector3d(1, 1, 1) : CameraCenter(image.cam_from_world));
    records.push_back({image.name,
                       Eigen::Vector3d(fix.latitude_deg, fix.longitude_deg, fix.altitude_m),
                       Eigen::Vector3d(0.1, 0.1, 0.1), ""});
  }
  WritePriorFile(records, dir / "priors.txt");
  return truth;
}

// The model's centres, mapped to WGS84 through its origin file, against the truth.
double GeodeticError(const std::string& model_path, const Reconstruction& truth) {
  const Reconstruction model = ReadColmapModel(model_path);
  const LocalEnuFrame model_frame(ReadGeoOrigin(model_path + "/geo_origin.txt"));
  const LocalEnuFrame truth_frame(kOrigin);
  double worst = 0.0;
  for (const auto& [id, image] : model.images) {
    const Eigen::Vector3d in_truth =
        truth_frame.FromGeodetic(model_frame.ToGeodetic(CameraCenter(image.cam_from_world)));
    worst = std::max(worst, (in_truth - CameraCenter(truth.images.at(id).cam_from_world)).norm());
  }
  return worst;
}

TEST(PriorAlignmentCommand, MapperWritesTheModelInEnuWithOriginAndGeoJson) {
  test::TempDir dir;
  const Reconstruction truth = SynthesizeWithPriors(dir);
  const test::CommandResult mapper =
      test::RunCommand(test::RamapCommand() + "mapper --database_path '" +
                       (dir / "scene/database.db") + "' --output_path '" + (dir / "sparse") +
                       "' --PosePrior.path '" + (dir / "priors.txt") + "' --Mapper.refine 1");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  EXPECT_NE(mapper.output.find("model 0 aligned to its priors: 30 of 30 priors"), std::string::npos)
      << mapper.output;
  EXPECT_LT(GeodeticError(dir / "sparse/0", truth), 0.1);
  std::ifstream geojson_file(dir / "sparse/0/cameras.geojson");
  const nlohmann::json geojson = nlohmann::json::parse(geojson_file);
  EXPECT_EQ(geojson["type"], "FeatureCollection");
  ASSERT_EQ(geojson["features"].size(), 30u);
  const nlohmann::json& first = geojson["features"][0];
  EXPECT_EQ(first["geometry"]["type"], "Point");
  EXPECT_NEAR(first["geometry"]["coordinates"][0].get<double>(), kOrigin.longitude_deg, 1e-3);
  EXPECT_NEAR(first["geometry"]["coordinates"][1].get<double>(), kOrigin.latitude_deg, 1e-3);
  EXPECT_EQ(first["properties"]["name"], truth.images.begin()->second.name);
  std::ifstream summary_file(dir / "sparse/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["components"][0]["prior_alignment"]["aligned"], true);
  EXPECT_EQ(summary["components"][0]["prior_alignment"]["used_in_bundle_adjustment"], true);
  // The block's former name, kept as an alias (README, "Renamed").
  EXPECT_EQ(summary["components"][0]["georegistration"]["georegistered"], true);
  EXPECT_EQ(summary["components"][0]["georegistration"]["num_inliers"], 30);
  // COLMAP opens the aligned model, its extra files beside it notwithstanding.
  if (test::ColmapAvailable()) {
    const test::CommandResult analyzer =
        test::RunCommand("colmap model_analyzer --path '" + (dir / "sparse/0") + "'");
    EXPECT_EQ(analyzer.exit_code, 0) << analyzer.output;
    EXPECT_NE(analyzer.output.find("Registered images: 30"), std::string::npos) << analyzer.output;
  }
}

TEST(PriorAlignmentCommand, ModelAlignerAlignsAModelMadeWithoutPriors) {
  test::TempDir dir;
  const Reconstruction truth = SynthesizeWithPriors(dir);
  ASSERT_EQ(
      test::RunCommand(test::RamapCommand() + "mapper --database_path '" +
                       (dir / "scene/database.db") + "' --output_path '" + (dir / "sparse") + "'")
          .exit_code,
      0);
  EXPECT_FALSE(fs::exists(dir / "sparse/0/geo_origin.txt"));
  const test::CommandResult aligner =
      test::RunCommand(test::RamapCommand() + "model_aligner --input_path '" + (dir / "sparse/0") +
                       "' --output_path '" + (dir / "aligned") + "' --PosePrior.path '" +
                       (dir / "priors.txt") + "' --output_type TXT");
  ASSERT_EQ(aligner.exit_code, 0) << aligner.output;
  EXPECT_NE(aligner.output.find("30 of 30 priors"), std::string::npos) << aligner.output;
  EXPECT_TRUE(fs::exists(dir / "aligned/images.txt"));
  EXPECT_TRUE(fs::exists(dir / "aligned/cameras.geojson"));
  EXPECT_LT(GeodeticError(dir / "aligned", truth), 0.1);
}

// Geotagged photos to a model aligned to their priors in one command: twelve templeRing views as
// JPEGs whose EXIF GPS is the true camera centre (scaled by 100 to a 60 m scene, in ENU about
// Lausanne); `ramap reconstruct` stores the tags as the database's priors and writes the model in
// metres.
TEST(PriorAlignmentCommand, ReconstructAlignsGeotaggedJpegsToTheirPriors) {
  RAMAP_REQUIRE_SHARED_DATA(folder, "middlebury_templeRing");
  std::vector<std::string> names;
  for (int k = 20; k < 32; ++k) names.push_back("templeR00" + std::to_string(k) + ".png");
  const std::map<std::string, Rigid3d> truth = GroundTruthByImageName(
      ReadGroundTruth(folder + "/templeR_par.txt", GroundTruthFormat::kMiddlebury), names);
  test::TempDir dir;
  fs::create_directories(dir / "images");
  const LocalEnuFrame frame(kOrigin);
  std::map<std::string, Eigen::Vector3d> expected;  // ENU about kOrigin, by JPEG name
  for (const std::string& name : names) {
    const Eigen::Vector3d enu = 100.0 * CameraCenter(truth.at(name));
    const std::string jpeg = name.substr(0, name.size() - 4) + ".jpg";
    expected[jpeg] = enu;
    const GeodeticPoint fix = frame.ToGeodetic(enu);
    test::WriteJpegWithGps(dir / ("images/" + jpeg), cv::imread(folder + "/" + name),
                           fix.latitude_deg, fix.longitude_deg, fix.altitude_m);
  }
  const test::CommandResult run = test::RunCommand(
      test::RamapCommand() + "reconstruct --image_path '" + (dir / "images") + "' --output_path '" +
      (dir / "out") +
      "' --ImageReader.camera_model PINHOLE --ImageReader.camera_params "
      "1520.4,1525.9,302.32,246.87 --ImageReader.single_camera 1 --FeatureExtraction.type sift "
      "--Matching.mode exhaustive --PosePrior.std_x_m 0.5 --PosePrior.std_y_m 0.5 "
      "--PosePrior.std_z_m 0.5");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("EXIF GPS of 12 stored as prior positions"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("aligned to its priors: 12 of 12 priors"), std::string::npos)
      << run.output;
  const Reconstruction model = ReadColmapModel(dir / "out/sparse/0");
  ASSERT_EQ(model.images.size(), 12u);
  const LocalEnuFrame model_frame(ReadGeoOrigin(dir / "out/sparse/0/geo_origin.txt"));
  double worst = 0.0;
  for (const auto& [id, image] : model.images) {
    const Eigen::Vector3d in_truth =
        frame.FromGeodetic(model_frame.ToGeodetic(CameraCenter(image.cam_from_world)));
    worst = std::max(worst, (in_truth - expected.at(image.name)).norm());
  }
  std::printf("geotagged templeRing: worst camera centre error %.3f m in a 60 m scene\n", worst);
  EXPECT_LT(worst, 1.0);
}

TEST(PriorAlignmentCommand, PriorsThatCannotAlignAreReported) {
  test::TempDir dir;
  SynthesizeWithPriors(dir, /*identical=*/true);
  const test::CommandResult mapper = test::RunCommand(
      test::RamapCommand() + "mapper --database_path '" + (dir / "scene/database.db") +
      "' --output_path '" + (dir / "sparse") + "' --PosePrior.path '" + (dir / "priors.txt") + "'");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  EXPECT_NE(mapper.output.find(
                "model 0 not aligned to its priors: the priors (or the model's centres) all "
                "coincide"),
            std::string::npos)
      << mapper.output;
  EXPECT_TRUE(fs::exists(dir / "sparse/0/images.bin"));
  EXPECT_FALSE(fs::exists(dir / "sparse/0/geo_origin.txt"));

  const test::CommandResult aligner =
      test::RunCommand(test::RamapCommand() + "model_aligner --input_path '" + (dir / "sparse/0") +
                       "' --output_path '" + (dir / "aligned") + "' --PosePrior.path '" +
                       (dir / "priors.txt") + "'");
  EXPECT_NE(aligner.exit_code, 0);
  EXPECT_NE(aligner.output.find("cannot align the model"), std::string::npos) << aligner.output;
  EXPECT_FALSE(fs::exists(dir / "aligned"));

  std::ofstream(dir / "broken.txt") << "frame_000001.png 46.5 6.5\n";
  const test::CommandResult broken =
      test::RunCommand(test::RamapCommand() + "mapper --database_path '" +
                       (dir / "scene/database.db") + "' --output_path '" + (dir / "sparse2") +
                       "' --PosePrior.path '" + (dir / "broken.txt") + "'");
  EXPECT_NE(broken.exit_code, 0);
  EXPECT_NE(broken.output.find("broken.txt:1"), std::string::npos) << broken.output;
  EXPECT_FALSE(fs::exists(dir / "sparse2"));
}

}  // namespace
}  // namespace ramap
