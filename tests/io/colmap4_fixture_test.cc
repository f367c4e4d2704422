// A database and a model that COLMAP 4.1.1 made itself (tests/data/colmap4, by
// scripts/make_colmap4_test_data.sh): read, mapped as well as the same features in a 3.8 database,
// updated in place without changing generation, and the model read and written back. Where the
// COLMAP 4.1.1 binary is built (scripts/peers.sh), it maps and reads what ramap wrote.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ramap/eval/pose_metrics.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/sqlite.h"
#include "ramap/mapper/mapper.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(RAMAP_SOURCE_DIR) + "/tests/data/colmap4";

std::vector<std::string> Names(const FeatureDatabase& database) {
  std::vector<std::string> names;
  for (const auto& [id, image] : database.images) names.push_back(image.name);
  return names;
}

PoseEvaluation Evaluate(const MapperResult& result, const FeatureDatabase& database) {
  return EvaluatePoses(PosesByName(result.reconstructions.front()),
                       PosesByName(ReadColmapModel(kData + "/ground_truth")), Names(database));
}

TEST(Colmap4Database, ReadAsColmapMadeIt) {
  const FeatureDatabase database = ReadColmapDatabase(kData + "/database.db");
  EXPECT_EQ(database.generation, DatabaseGeneration::kColmap4);
  EXPECT_EQ(database.images.size(), 10u);
  // COLMAP's feature importer makes one rig per camera and one frame per image.
  EXPECT_EQ(database.rigs.size(), database.cameras.size());
  EXPECT_EQ(database.frames.size(), database.images.size());
  size_t verified = 0;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    verified += !geometry.inlier_matches.empty();
  }
  EXPECT_GE(verified, 20u);
}

// The same features as a 3.8 database give the same model, and it is the true one.
TEST(Colmap4Database, MapsAsTheSameFeaturesIn38) {
  test::TempDir dir;
  const FeatureDatabase database =
      ReadColmapDatabase(kData + "/database.db", MapperDatabaseReadOptions());
  WriteColmapDatabase(database, dir / "38.db", DatabaseGeneration::kColmap38);
  const FeatureDatabase as38 = ReadColmapDatabase(dir / "38.db", MapperDatabaseReadOptions());
  // One thread: Ceres' multi-threaded bundle adjustment differs in the last digits from run to
  // run, on one database as between two.
  MapperOptions options;
  options.num_threads = 1;
  options.bundle_adjustment.num_threads = 1;
  const MapperResult from4 = RunMapper(database, options, "colmap4");
  const MapperResult from38 = RunMapper(as38, options, "colmap38");
  const PoseEvaluation evaluation4 = Evaluate(from4, database);
  const PoseEvaluation evaluation38 = Evaluate(from38, as38);
  ASSERT_EQ(evaluation4.auc.size(), evaluation38.auc.size());
  for (size_t k = 0; k < evaluation4.auc.size(); ++k) {
    EXPECT_EQ(evaluation4.auc[k], evaluation38.auc[k])
        << "AUC@" << evaluation4.auc_thresholds_deg[k];
  }
  // Half a pixel of noise on 10 images: every image registered, AUC@3 well above 90.
  EXPECT_EQ(from4.reconstructions.front().images.size(), 10u);
  EXPECT_GT(evaluation4.auc[1], 0.9);
}

TEST(Colmap4Database, UpdatedInPlaceStays4x) {
  test::TempDir dir;
  fs::copy_file(kData + "/database.db", dir / "db.db");
  FeatureDatabase database = ReadColmapDatabase(dir / "db.db");
  database.two_view_geometries.erase(database.two_view_geometries.begin());
  WriteColmapDatabaseMatches(database, dir / "db.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db");
  EXPECT_EQ(read.generation, DatabaseGeneration::kColmap4);
  EXPECT_EQ(read.two_view_geometries.size(), database.two_view_geometries.size());
  EXPECT_EQ(read.frames.size(), 10u);
  sqlite::Connection db(dir / "db.db", sqlite::Connection::OpenExisting(), "db");
  EXPECT_EQ(DetectDatabaseLayout(db).user_version, 4010100);

  const std::string colmap4 = test::Colmap4Binary();
  if (colmap4.empty()) GTEST_SKIP() << "no COLMAP 4.1.1 build (scripts/peers.sh): not run on it";
  fs::create_directories(dir / "sparse");
  const test::CommandResult mapped = test::RunCommand(
      "'" + colmap4 + "' mapper --database_path '" + (dir / "db.db") + "' --image_path '" +
      dir.path() + "' --output_path '" + (dir / "sparse") + "' 2>&1");
  ASSERT_EQ(mapped.exit_code, 0) << mapped.output;
  EXPECT_GE(ReadColmapModel(dir / "sparse/0").images.size(), 9u);
}

TEST(Colmap4Model, ReadAndWrittenBack) {
  const Reconstruction model = ReadColmapModel(kData + "/global_mapper_model");
  EXPECT_GE(model.images.size(), 9u);
  EXPECT_EQ(model.frames.size(), model.images.size());
  EXPECT_FALSE(model.rigs.empty());
  test::TempDir dir;
  WriteColmapModel(model, dir / "model", ModelFormat::kBinary);
  const Reconstruction read = ReadColmapModel(dir / "model");
  EXPECT_EQ(read.images.size(), model.images.size());
  EXPECT_EQ(read.points3D.size(), model.points3D.size());
  EXPECT_EQ(read.frames.size(), model.frames.size());
  for (const char* file : {"cameras.bin", "images.bin", "points3D.bin", "rigs.bin", "frames.bin"}) {
    EXPECT_TRUE(fs::exists(dir / (std::string("model/") + file))) << file;
  }

  const std::string colmap4 = test::Colmap4Binary();
  if (colmap4.empty()) GTEST_SKIP() << "no COLMAP 4.1.1 build (scripts/peers.sh): not run on it";
  const test::CommandResult converted =
      test::RunCommand("'" + colmap4 + "' model_converter --input_path '" + (dir / "model") +
                       "' --output_path '" + (dir / "model") + "' --output_type TXT 2>&1");
  ASSERT_EQ(converted.exit_code, 0) << converted.output;
  EXPECT_TRUE(fs::exists(dir / "model/frames.txt"));
}

}  // namespace
}  // namespace ramap
