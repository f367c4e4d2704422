// The three generations of COLMAP's database (io/colmap_database_schema.h): each written and read
// back, a 3.10 database built from COLMAP 3.11's schema by plain SQL, a 4.x database updated in
// place, and the defects of each generation named.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/sqlite.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

using test::TempDir;

// A small scene with two cameras and a GPS-like prior on every third image, one with a covariance.
FeatureDatabase SmallDatabase() {
  SyntheticSceneOptions options;
  options.num_images = 8;
  options.num_points = 300;
  options.second_camera = options.camera;
  options.second_camera->params[0] *= 1.1;
  FeatureDatabase database = BuildSyntheticScene(options).database;
  for (auto& [image_id, image] : database.images) {
    if (image_id % 3 != 0) continue;
    image.prior_translation = Eigen::Vector3d(47.0 + image_id * 1e-4, 8.5, 400.0 + image_id);
    image.prior_coordinate_system = PriorCoordinateSystem::kWgs84;
  }
  database.images.at(3).prior_position_covariance = Eigen::Vector3d(4, 9, 16).asDiagonal();
  return database;
}

void ExpectSameFeatures(const FeatureDatabase& expected, const FeatureDatabase& actual) {
  ASSERT_EQ(expected.images.size(), actual.images.size());
  for (const auto& [image_id, image] : expected.images) {
    const Image& read = actual.images.at(image_id);
    EXPECT_EQ(read.name, image.name);
    EXPECT_EQ(read.camera_id, image.camera_id);
    ASSERT_EQ(read.prior_translation.has_value(), image.prior_translation.has_value()) << image_id;
    if (image.prior_translation) {
      EXPECT_EQ(*read.prior_translation, *image.prior_translation);
    }
    EXPECT_EQ(actual.keypoints.at(image_id).data, expected.keypoints.at(image_id).data);
  }
  ASSERT_EQ(expected.cameras.size(), actual.cameras.size());
  for (const auto& [camera_id, camera] : expected.cameras) {
    EXPECT_EQ(actual.cameras.at(camera_id).params, camera.params);
  }
  ASSERT_EQ(expected.two_view_geometries.size(), actual.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : expected.two_view_geometries) {
    const TwoViewGeometry& read = actual.two_view_geometries.at(pair_id);
    EXPECT_EQ(read.inlier_matches.size(), geometry.inlier_matches.size());
    EXPECT_TRUE(read.F.isApprox(geometry.F));
    EXPECT_TRUE(read.E.isApprox(geometry.E));
    EXPECT_TRUE(read.cam2_from_cam1.rotation.isApprox(geometry.cam2_from_cam1.rotation));
  }
}

class EachGeneration : public testing::TestWithParam<DatabaseGeneration> {};

TEST_P(EachGeneration, WrittenAndReadBackWithItsGeneration) {
  TempDir dir;
  const FeatureDatabase database = SmallDatabase();
  WriteColmapDatabase(database, dir / "db.db", GetParam());
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db");
  EXPECT_EQ(read.generation, GetParam());
  ExpectSameFeatures(database, read);
  if (GetParam() == DatabaseGeneration::kColmap38) return;
  // 3.10 on: the prior table holds the coordinate system and the covariance.
  EXPECT_EQ(read.images.at(6).prior_coordinate_system, PriorCoordinateSystem::kWgs84);
  ASSERT_TRUE(read.images.at(3).prior_position_covariance.has_value());
  EXPECT_EQ(read.images.at(3).prior_position_covariance->diagonal(), Eigen::Vector3d(4, 9, 16));
  EXPECT_FALSE(read.images.at(6).prior_position_covariance.has_value());
  if (GetParam() != DatabaseGeneration::kColmap4) return;
  // One rig per camera, one frame per image, as COLMAP 4's own feature extractor makes them.
  ASSERT_EQ(read.rigs.size(), 2u);
  ASSERT_EQ(read.frames.size(), 8u);
  EXPECT_EQ(read.frames.at(4).rig_id, read.images.at(4).camera_id);
  EXPECT_EQ(read.frames.at(4).data.at(0).data_id, 4u);
  sqlite::Connection db(dir / "db.db", sqlite::Connection::OpenExisting(), "db");
  EXPECT_EQ(DetectDatabaseLayout(db).user_version, 4010100);
}

INSTANTIATE_TEST_SUITE_P(Generations, EachGeneration,
                         testing::Values(DatabaseGeneration::kColmap38,
                                         DatabaseGeneration::kColmap310,
                                         DatabaseGeneration::kColmap4));

// COLMAP 3.11's schema (src/colmap/scene/database.cc of that release), by plain SQL: nothing of
// ramap's writer is involved.
void Create311Database(const std::string& path) {
  sqlite::Connection db(path, sqlite::Connection::Create(), path);
  db.Execute(
      "CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER "
      "NOT NULL, width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, "
      "prior_focal_length INTEGER NOT NULL);"
      "CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT "
      "NULL UNIQUE, camera_id INTEGER NOT NULL);"
      "CREATE TABLE pose_priors (image_id INTEGER PRIMARY KEY NOT NULL, position BLOB, "
      "coordinate_system INTEGER NOT NULL, position_covariance BLOB);"
      "CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols "
      "INTEGER NOT NULL, data BLOB);"
      "CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, "
      "cols INTEGER NOT NULL, data BLOB);"
      "CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols "
      "INTEGER NOT NULL, data BLOB);"
      "CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT "
      "NULL, cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, "
      "qvec BLOB, tvec BLOB);"
      "PRAGMA user_version = 3110000;");
  const double params[4] = {500, 500, 320, 240};
  sqlite::Statement camera(db, "INSERT INTO cameras VALUES(1, 1, 640, 480, ?, 1)");
  camera.BindBlob(1, params, sizeof(params));
  camera.Run();
  db.Execute("INSERT INTO images VALUES(1, 'a.png', 1); INSERT INTO images VALUES(2, 'b.png', 1)");
  const double position[3] = {10, 20, 30};
  const double covariance[9] = {0.25, 0, 0, 0, 0.25, 0, 0, 0, 1};
  sqlite::Statement prior(db, "INSERT INTO pose_priors VALUES(2, ?, 1, ?)");
  prior.BindBlob(1, position, sizeof(position));
  prior.BindBlob(2, covariance, sizeof(covariance));
  prior.Run();
}

TEST(ColmapDatabase310, PosePriorsByImageFromColmapsSchema) {
  TempDir dir;
  Create311Database(dir / "db.db");
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db");
  EXPECT_EQ(read.generation, DatabaseGeneration::kColmap310);
  EXPECT_FALSE(read.images.at(1).prior_translation.has_value());
  ASSERT_TRUE(read.images.at(2).prior_translation.has_value());
  EXPECT_EQ(*read.images.at(2).prior_translation, Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(read.images.at(2).prior_coordinate_system, PriorCoordinateSystem::kCartesian);
  EXPECT_EQ(read.images.at(2).prior_position_covariance->diagonal(),
            Eigen::Vector3d(0.25, 0.25, 1));
}

// Reading a defective database throws InputError naming each of `parts`, and leaves the file as
// it was.
void ExpectRefused(const std::string& path, const std::vector<std::string>& parts) {
  const std::string before = test::ReadFileBytes(path);
  test::ExpectInputError([&] { ReadColmapDatabase(path); }, parts);
  EXPECT_EQ(test::ReadFileBytes(path), before);
}

TEST(ColmapDatabaseGenerationsBadInput, EachDefectNamed) {
  TempDir dir;
  // No prior columns, no pose_priors, no frames: a generation ramap does not know.
  Create311Database(dir / "unknown.db");
  sqlite::Connection(dir / "unknown.db", sqlite::Connection::Create(), "")
      .Execute("DROP TABLE pose_priors");
  ExpectRefused(dir / "unknown.db", {"unknown.db", "'prior_qw'", "'pose_priors'", "'frames'"});

  Create311Database(dir / "system.db");
  sqlite::Connection(dir / "system.db", sqlite::Connection::Create(), "")
      .Execute("UPDATE pose_priors SET coordinate_system = 7");
  ExpectRefused(dir / "system.db", {"pose_priors", "image 2", "unknown coordinate system 7"});

  // A 4.x database whose frame holds an image of a camera its rig does not have.
  FeatureDatabase database = SmallDatabase();
  WriteColmapDatabase(database, dir / "rig.db", DatabaseGeneration::kColmap4);
  sqlite::Connection(dir / "rig.db", sqlite::Connection::Create(), "")
      .Execute("UPDATE frame_data SET sensor_id = 2 WHERE frame_id = 3");
  ExpectRefused(dir / "rig.db", {"frame 3", "camera 2 is not a sensor of rig 1"});

  WriteColmapDatabase(database, dir / "camera.db", DatabaseGeneration::kColmap4);
  sqlite::Connection(dir / "camera.db", sqlite::Connection::Create(), "")
      .Execute("UPDATE rigs SET ref_sensor_id = 9 WHERE rig_id = 2");
  ExpectRefused(dir / "camera.db", {"rig 2", "camera 9 is not in table cameras"});

  WriteColmapDatabase(database, dir / "frames.db", DatabaseGeneration::kColmap4);
  sqlite::Connection(dir / "frames.db", sqlite::Connection::Create(), "")
      .Execute("DROP TABLE frame_data");
  ExpectRefused(dir / "frames.db", {"missing table 'frame_data'"});
}

// A 3.8 database that COLMAP 4 opened: its tables added, the old prior columns kept.
TEST(ColmapDatabase4, UpgradedDatabaseKeepsItsOldPriors) {
  TempDir dir;
  const FeatureDatabase database = SmallDatabase();
  WriteColmapDatabase(database, dir / "db.db", DatabaseGeneration::kColmap38);
  {
    sqlite::Connection db(dir / "db.db", sqlite::Connection::Create(), "");
    for (const std::string& statement : SchemaStatements(DatabaseGeneration::kColmap4)) {
      if (statement.find("TABLE rigs") != std::string::npos ||
          statement.find("TABLE rig_sensors") != std::string::npos ||
          statement.find("TABLE frames") != std::string::npos ||
          statement.find("TABLE frame_data") != std::string::npos) {
        db.Execute(statement);
      }
    }
    db.Execute("PRAGMA user_version = 4010100");
  }
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db");
  EXPECT_EQ(read.generation, DatabaseGeneration::kColmap4);
  ExpectSameFeatures(database, read);
  EXPECT_TRUE(read.rigs.empty());
}

// `ramap matcher` replaces the matches of a 4.x database in place: it stays 4.x, with COLMAP 4's
// NULL for what is unknown.
TEST(ColmapDatabase4, MatchesUpdatedInPlaceKeepTheGeneration) {
  TempDir dir;
  FeatureDatabase database = SmallDatabase();
  WriteColmapDatabase(database, dir / "db.db", DatabaseGeneration::kColmap4);
  TwoViewGeometry& geometry = database.two_view_geometries.begin()->second;
  geometry.F.setZero();
  geometry.cam2_from_cam1 = Rigid3d();
  WriteColmapDatabaseMatches(database, dir / "db.db");

  sqlite::Connection db(dir / "db.db", sqlite::Connection::OpenExisting(), "db");
  const DatabaseLayout layout = DetectDatabaseLayout(db);
  EXPECT_EQ(layout.generation, DatabaseGeneration::kColmap4);
  EXPECT_EQ(layout.user_version, 4010100);
  sqlite::Statement row(db,
                        "SELECT F IS NULL, qvec IS NULL, E IS NULL FROM two_view_geometries "
                        "WHERE pair_id = ?");
  row.BindInt64(1, static_cast<int64_t>(database.two_view_geometries.begin()->first));
  ASSERT_TRUE(row.Step());
  EXPECT_EQ(row.ColumnInt64(0), 1);
  EXPECT_EQ(row.ColumnInt64(1), 1);
  EXPECT_EQ(row.ColumnInt64(2), 0);
  const FeatureDatabase read = ReadColmapDatabase(dir / "db.db");
  EXPECT_EQ(read.frames.size(), 8u);
  ExpectSameFeatures(database, read);
}

TEST(DatabaseGenerationNames, RoundTripAndRefusal) {
  for (const DatabaseGeneration generation :
       {DatabaseGeneration::kColmap38, DatabaseGeneration::kColmap310,
        DatabaseGeneration::kColmap4}) {
    EXPECT_EQ(DatabaseGenerationFromName(DatabaseGenerationName(generation), "--x"), generation);
  }
  EXPECT_EQ(DatabaseGenerationFromName("4.1", "--x"), DatabaseGeneration::kColmap4);
  EXPECT_THROW(DatabaseGenerationFromName("5", "--Database.generation"), InputError);
}

}  // namespace
}  // namespace ramap
