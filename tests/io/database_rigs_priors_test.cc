// Pose priors, rigs and frames of a COLMAP database: written into each generation's tables and
// read back as they were, trivial rigs where none are given, and each defect named.
#include "ramap/io/database_rigs_priors.h"

#include <gtest/gtest.h>

#include <limits>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

using sqlite::Connection;

void CreateEmpty(Connection& db, DatabaseGeneration generation) {
  for (const std::string& statement : SchemaStatements(generation)) db.Execute(statement);
}

// Cameras 1 and 2; images 1, 3 (camera 1) and 2, 4 (camera 2); priors on images 1 (WGS84, with a
// covariance and gravity), 2 (Cartesian, nothing else) and 4 (undefined system).
FeatureDatabase WithPriors() {
  FeatureDatabase database;
  for (uint32_t camera_id : {1u, 2u}) {
    database.cameras[camera_id] = test::VgaPinholeCamera();
    database.cameras[camera_id].camera_id = camera_id;
  }
  for (uint32_t id = 1; id <= 4; ++id) {
    database.images[id].image_id = id;
    database.images[id].name = "image" + std::to_string(id) + ".png";
    database.images[id].camera_id = id % 2 == 1 ? 1 : 2;
  }
  Image& first = database.images.at(1);
  first.prior_translation = Eigen::Vector3d(48.137, 11.575, 519.5);
  first.prior_coordinate_system = PriorCoordinateSystem::kWgs84;
  Eigen::Matrix3d covariance;
  covariance << 4, 0.5, 0, 0.5, 9, 0.1, 0, 0.1, 16;
  first.prior_position_covariance = covariance;
  first.prior_gravity = Eigen::Vector3d(0, 1, 0);
  Image& second = database.images.at(2);
  second.prior_translation = Eigen::Vector3d(-3.5, 2.0, 0.25);
  second.prior_coordinate_system = PriorCoordinateSystem::kCartesian;
  database.images.at(4).prior_translation = Eigen::Vector3d(1, 2, 3);
  return database;
}

// `database` without its priors, as the images table alone gives it.
FeatureDatabase WithoutPriors(FeatureDatabase database) {
  for (auto& [id, image] : database.images) {
    image.prior_translation.reset();
    image.prior_coordinate_system = PriorCoordinateSystem::kUndefined;
    image.prior_position_covariance.reset();
    image.prior_gravity.reset();
  }
  return database;
}

// Writes the priors of WithPriors() into an empty database of `generation`, runs `edit` on it and
// reads them back into the same images without priors.
FeatureDatabase RoundTrip(const std::string& path, DatabaseGeneration generation,
                          const std::function<void(Connection&)>& edit = nullptr,
                          FeatureDatabase* read_into = nullptr) {
  Connection db(path, Connection::Create(), "project.db");
  CreateEmpty(db, generation);
  WriteDatabasePosePriors(WithPriors(), generation, db);
  if (edit) edit(db);
  FeatureDatabase read = read_into != nullptr ? *read_into : WithoutPriors(WithPriors());
  ReadDatabasePosePriors(db, DetectDatabaseLayout(db), &read);
  return read;
}

TEST(DatabaseRigsPriors, PriorsReadBackFromEachGenerationThatStoresThem) {
  test::TempDir dir;
  for (const DatabaseGeneration generation :
       {DatabaseGeneration::kColmap310, DatabaseGeneration::kColmap4}) {
    const FeatureDatabase read =
        RoundTrip(dir / (DatabaseGenerationName(generation) + ".db"), generation);
    const FeatureDatabase expected = WithPriors();
    const bool with_gravity = generation == DatabaseGeneration::kColmap4;
    for (const auto& [id, image] : expected.images) {
      const Image& got = read.images.at(id);
      SCOPED_TRACE("generation " + DatabaseGenerationName(generation) + ", image " +
                   std::to_string(id));
      ASSERT_EQ(got.prior_translation.has_value(), image.prior_translation.has_value());
      if (!image.prior_translation) continue;
      EXPECT_EQ(*got.prior_translation, *image.prior_translation);  // float64 blobs: bit for bit
      EXPECT_EQ(got.prior_coordinate_system, image.prior_coordinate_system);
      // An unknown covariance or gravity is written as NaN and read back as none.
      ASSERT_EQ(got.prior_position_covariance.has_value(),
                image.prior_position_covariance.has_value());
      if (image.prior_position_covariance) {
        EXPECT_EQ(*got.prior_position_covariance, *image.prior_position_covariance);
      }
      ASSERT_EQ(got.prior_gravity.has_value(), with_gravity && image.prior_gravity.has_value());
      if (got.prior_gravity) EXPECT_EQ(*got.prior_gravity, *image.prior_gravity);
    }
  }
}

TEST(DatabaseRigsPriors, ColmapThreeEightKeepsPriorsInTheImagesTableAlone) {
  test::TempDir dir;
  const FeatureDatabase read = RoundTrip(dir / "38.db", DatabaseGeneration::kColmap38);
  for (const auto& [id, image] : read.images) EXPECT_FALSE(image.prior_translation) << id;
}

TEST(DatabaseRigsPriors, ATablesPriorReplacesOneFromTheOldColumns) {
  test::TempDir dir;
  FeatureDatabase old_columns = WithoutPriors(WithPriors());
  old_columns.images.at(1).prior_translation = Eigen::Vector3d(0, 0, 0);
  old_columns.images.at(3).prior_translation = Eigen::Vector3d(7, 7, 7);
  const FeatureDatabase read =
      RoundTrip(dir / "4.db", DatabaseGeneration::kColmap4, nullptr, &old_columns);
  EXPECT_EQ(*read.images.at(1).prior_translation, Eigen::Vector3d(48.137, 11.575, 519.5));
  // Image 3 has no row in the table: its old prior stays.
  EXPECT_EQ(*read.images.at(3).prior_translation, Eigen::Vector3d(7, 7, 7));
}

TEST(DatabaseRigsPriors, PriorsOfOtherSensorsSayNothingOfImages) {
  test::TempDir dir;
  const FeatureDatabase read =
      RoundTrip(dir / "imu.db", DatabaseGeneration::kColmap4, [](Connection& db) {
        db.Execute("UPDATE pose_priors SET corr_sensor_type = 1 WHERE corr_data_id = 2");
      });
  EXPECT_FALSE(read.images.at(2).prior_translation);
  EXPECT_TRUE(read.images.at(1).prior_translation);
}

TEST(DatabaseRigsPriors, DefectivePriorsAreNamed) {
  test::TempDir dir;
  const auto refused = [&](const std::string& name, DatabaseGeneration generation,
                           const std::string& sql, const std::vector<std::string>& parts) {
    test::ExpectInputError(
        [&] { RoundTrip(dir / name, generation, [&](Connection& db) { db.Execute(sql); }); },
        parts);
  };
  std::vector<std::string> expected = {"project.db", "image 1", "unknown coordinate system 5"};
  refused("system.db", DatabaseGeneration::kColmap310,
          "UPDATE pose_priors SET coordinate_system = 5 WHERE image_id = 1", expected);
  refused("blob.db", DatabaseGeneration::kColmap310,
          "UPDATE pose_priors SET position = zeroblob(16) WHERE image_id = 2",
          {"project.db", "image 2, position", "blob has 16 bytes, expected 24"});
  refused("image.db", DatabaseGeneration::kColmap310,
          "UPDATE pose_priors SET image_id = 9 WHERE image_id = 4",
          {"project.db", "image 9 is not in table images"});
  refused("camera.db", DatabaseGeneration::kColmap4,
          "UPDATE pose_priors SET corr_sensor_id = 2 WHERE corr_data_id = 1",
          {"project.db", "prior 1", "'image1.png' was taken by camera 1, not camera 2"});
  refused("sensor.db", DatabaseGeneration::kColmap4,
          "UPDATE pose_priors SET corr_sensor_type = 7 WHERE corr_data_id = 1",
          {"project.db", "unknown sensor type 7"});
}

// Cameras 1 and 2 on one rig (camera 2 calibrated in it); frames 10 and 11 holding one image of
// each camera.
FeatureDatabase WithRig() {
  FeatureDatabase database = WithoutPriors(WithPriors());
  Rig rig;
  rig.rig_id = 5;
  rig.ref_sensor = {SensorType::kCamera, 1};
  rig.sensors.push_back(
      {{SensorType::kCamera, 2},
       Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY())),
               Eigen::Vector3d(0.3, 0, 0))});
  database.rigs[5] = rig;
  for (const uint32_t frame_id : {10u, 11u}) {
    Frame frame;
    frame.frame_id = frame_id;
    frame.rig_id = 5;
    const uint32_t first = frame_id == 10 ? 1 : 3;  // images 1, 2 and 3, 4
    frame.data = {{{SensorType::kCamera, 1}, first}, {{SensorType::kCamera, 2}, first + 1}};
    database.frames[frame_id] = frame;
  }
  return database;
}

void ExpectSameRigs(const FeatureDatabase& expected, const FeatureDatabase& read) {
  ASSERT_EQ(read.rigs.size(), expected.rigs.size());
  for (const auto& [rig_id, rig] : expected.rigs) {
    const Rig& got = read.rigs.at(rig_id);
    EXPECT_EQ(got.ref_sensor, rig.ref_sensor);
    ASSERT_EQ(got.sensors.size(), rig.sensors.size());
    for (size_t k = 0; k < rig.sensors.size(); ++k) {
      EXPECT_EQ(got.sensors[k].sensor, rig.sensors[k].sensor);
      ASSERT_EQ(got.sensors[k].sensor_from_rig.has_value(),
                rig.sensors[k].sensor_from_rig.has_value());
      if (rig.sensors[k].sensor_from_rig) {
        EXPECT_EQ(got.sensors[k].sensor_from_rig->rotation.coeffs(),
                  rig.sensors[k].sensor_from_rig->rotation.coeffs());
        EXPECT_EQ(got.sensors[k].sensor_from_rig->translation,
                  rig.sensors[k].sensor_from_rig->translation);
      }
    }
  }
  ASSERT_EQ(read.frames.size(), expected.frames.size());
  for (const auto& [frame_id, frame] : expected.frames) {
    const Frame& got = read.frames.at(frame_id);
    EXPECT_EQ(got.rig_id, frame.rig_id);
    ASSERT_EQ(got.data.size(), frame.data.size());
    for (size_t k = 0; k < frame.data.size(); ++k) {
      EXPECT_EQ(got.data[k].sensor, frame.data[k].sensor);
      EXPECT_EQ(got.data[k].data_id, frame.data[k].data_id);
    }
  }
}

FeatureDatabase RigRoundTrip(const std::string& path, const FeatureDatabase& written,
                             const std::string& sql = "") {
  Connection db(path, Connection::Create(), "project.db");
  CreateEmpty(db, DatabaseGeneration::kColmap4);
  WriteDatabaseRigsAndFrames(written, db);
  if (!sql.empty()) db.Execute(sql);
  FeatureDatabase read = written;
  read.rigs.clear();
  read.frames.clear();
  ReadDatabaseRigsAndFrames(db, &read);
  return read;
}

TEST(DatabaseRigsPriors, RigsAndFramesReadBackAsWritten) {
  test::TempDir dir;
  const FeatureDatabase database = WithRig();
  ExpectSameRigs(database, RigRoundTrip(dir / "rig.db", database));
  const RigSummary summary = SummarizeRigs(database);
  EXPECT_EQ(summary.num_rigs, 1u);
  EXPECT_EQ(summary.num_frames, 2u);
  EXPECT_EQ(summary.num_multi_camera_frames, 2u);
  EXPECT_EQ(summary.max_cameras_per_frame, 2u);
}

TEST(DatabaseRigsPriors, WithoutRigsOneRigPerCameraAndOneFramePerImage) {
  test::TempDir dir;
  const FeatureDatabase database = WithoutPriors(WithPriors());
  const Rigs rigs = RigsOrOnePerCamera(database);
  ASSERT_EQ(rigs.size(), 2u);
  for (const uint32_t camera_id : {1u, 2u}) {
    EXPECT_EQ(rigs.at(camera_id).ref_sensor, (SensorId{SensorType::kCamera, camera_id}));
    EXPECT_TRUE(rigs.at(camera_id).sensors.empty());
  }
  const Frames frames = FramesOrOnePerImage(database);
  ASSERT_EQ(frames.size(), 4u);
  for (const auto& [image_id, image] : database.images) {
    const Frame& frame = frames.at(image_id);
    EXPECT_EQ(frame.rig_id, image.camera_id);
    ASSERT_EQ(frame.data.size(), 1u);
    EXPECT_EQ(frame.data[0].data_id, image_id);
  }
  // Written so and read back: the database then holds those trivial rigs and frames.
  FeatureDatabase trivial = database;
  trivial.rigs = rigs;
  trivial.frames = frames;
  ExpectSameRigs(trivial, RigRoundTrip(dir / "trivial.db", database));
  const RigSummary summary = SummarizeRigs(trivial);
  EXPECT_EQ(summary.num_multi_camera_frames, 0u);
  EXPECT_EQ(summary.max_cameras_per_frame, 1u);
  // A database's own rigs are kept.
  EXPECT_EQ(RigsOrOnePerCamera(WithRig()).size(), 1u);
  EXPECT_EQ(FramesOrOnePerImage(WithRig()).size(), 2u);
}

TEST(DatabaseRigsPriors, RigsAndFramesThatDoNotHoldTogetherAreNamed) {
  test::TempDir dir;
  const FeatureDatabase database = WithRig();
  test::ExpectInputError(
      [&] {
        RigRoundTrip(dir / "a.db", database, "UPDATE frames SET rig_id = 8 WHERE frame_id = 11");
      },
      {"project.db", "frame 11", "rig 8 is not in table rigs"});
  test::ExpectInputError(
      [&] {
        RigRoundTrip(dir / "b.db", database,
                     "UPDATE frame_data SET data_id = 99 WHERE frame_id = 10 AND sensor_id = 2");
      },
      {"project.db", "frame 10", "image 99 is not in table images"});
  // Image 3 is camera 1's, not camera 2's.
  test::ExpectInputError(
      [&] {
        RigRoundTrip(dir / "c.db", database,
                     "UPDATE frame_data SET data_id = 5 WHERE frame_id = 11 AND sensor_id = 2; "
                     "UPDATE frame_data SET data_id = 4 WHERE frame_id = 11 AND sensor_id = 1");
      },
      {"project.db", "frame 11", "image 4 'image4.png' was taken by camera 2, not by camera 1"});
  test::ExpectInputError(
      [&] {
        RigRoundTrip(dir / "d.db", database,
                     "UPDATE rig_sensors SET sensor_from_rig = zeroblob(8) WHERE rig_id = 5");
      },
      {"project.db", "rig 5", "sensor_from_rig", "expected 56"});
}

}  // namespace
}  // namespace ramap
