#include "ramap/io/database_rigs_priors.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "ramap/util/error.h"

namespace ramap {
namespace {

using sqlite::BlobView;
using sqlite::Connection;
using sqlite::Statement;

[[noreturn]] void Fail(const Connection& db, const std::string& problem) {
  throw InputError(db.source(), problem);
}

// A float64 blob of `count` values into `values`: false when NULL or empty, or when a value is
// NaN or infinite (COLMAP writes an unknown prior as NaN). A blob of another size fails.
bool FiniteBlob(const Connection& db, const Statement& row, int column, size_t count,
                double* values, const std::string& what) {
  const BlobView blob = row.ColumnBlob(column);
  if (blob.size == 0) return false;
  if (blob.size != count * sizeof(double)) {
    Fail(db, what + ": blob has " + std::to_string(blob.size) + " bytes, expected " +
                 std::to_string(count * sizeof(double)) + " (" + std::to_string(count) +
                 " float64)");
  }
  std::memcpy(values, blob.data, blob.size);
  for (size_t i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

PriorCoordinateSystem CheckedCoordinateSystem(const Connection& db, int64_t value,
                                              const std::string& what) {
  if (value < -1 || value > 1) {
    Fail(db, what + ": unknown coordinate system " + std::to_string(value) +
                 " (COLMAP's are -1 undefined, 0 WGS84, 1 Cartesian)");
  }
  return static_cast<PriorCoordinateSystem>(value);
}

// Position, coordinate system, covariance and gravity of one prior row into `image`; the columns
// are position, coordinate_system, position_covariance, gravity from `first` on.
void SetPrior(const Connection& db, const Statement& row, int first, const std::string& what,
              Image* image) {
  Eigen::Vector3d position;
  if (!FiniteBlob(db, row, first, 3, position.data(), what + ", position")) return;
  image->prior_translation = position;
  image->prior_coordinate_system =
      CheckedCoordinateSystem(db, row.ColumnInt64(first + 1), what + ", coordinate_system");
  Eigen::Matrix3d covariance;
  if (FiniteBlob(db, row, first + 2, 9, covariance.data(), what + ", position_covariance")) {
    image->prior_position_covariance = covariance;
  }
  Eigen::Vector3d gravity;
  if (FiniteBlob(db, row, first + 3, 3, gravity.data(), what + ", gravity")) {
    image->prior_gravity = gravity;
  }
}

Image& PriorImage(const Connection& db, FeatureDatabase* database, int64_t image_id,
                  const std::string& what) {
  const auto found = database->images.find(static_cast<uint32_t>(image_id));
  if (image_id < 0 || image_id > std::numeric_limits<uint32_t>::max() ||
      found == database->images.end()) {
    Fail(db, what + ": image " + std::to_string(image_id) + " is not in table images");
  }
  return found->second;
}

void ReadPriorsByImage(Connection& db, const DatabaseLayout& layout, FeatureDatabase* database) {
  Statement row(db, std::string("SELECT image_id, position, coordinate_system, ") +
                        (layout.pose_prior_covariance ? "position_covariance" : "NULL") +
                        ", NULL FROM pose_priors");
  while (row.Step()) {
    const int64_t image_id = row.ColumnInt64(0);
    const std::string what = "pose_priors, image " + std::to_string(image_id);
    SetPrior(db, row, 1, what, &PriorImage(db, database, image_id, what));
  }
}

void ReadPriorsBySensorData(Connection& db, const DatabaseLayout& layout,
                            FeatureDatabase* database) {
  Statement row(db, std::string("SELECT pose_prior_id, corr_data_id, corr_sensor_id, "
                                "corr_sensor_type, position, coordinate_system, ") +
                        (layout.pose_prior_covariance ? "position_covariance" : "NULL") + ", " +
                        (layout.pose_prior_gravity ? "gravity" : "NULL") + " FROM pose_priors");
  while (row.Step()) {
    const std::string what = "pose_priors, prior " + std::to_string(row.ColumnInt64(0));
    const std::optional<SensorType> type = SensorTypeFromId(row.ColumnInt64(3));
    if (!type) {
      Fail(db, what + ": unknown sensor type " + std::to_string(row.ColumnInt64(3)) +
                   " (COLMAP's are 0 camera, 1 IMU)");
    }
    if (*type != SensorType::kCamera) continue;  // priors of other sensors say nothing of images
    Image& image = PriorImage(db, database, row.ColumnInt64(1), what);
    if (row.ColumnInt64(2) != image.camera_id) {
      Fail(db, what + ": image " + std::to_string(image.image_id) + " '" + image.name +
                   "' was taken by camera " + std::to_string(image.camera_id) + ", not camera " +
                   std::to_string(row.ColumnInt64(2)));
    }
    SetPrior(db, row, 4, what, &image);
  }
}

// A sensor id read from (id, type) columns; fails on an unknown type, or a camera that is not in
// table cameras.
SensorId CheckedSensor(const Connection& db, const FeatureDatabase& database, int64_t id,
                       int64_t type, const std::string& what) {
  const std::optional<SensorType> sensor_type = SensorTypeFromId(type);
  if (!sensor_type || *sensor_type == SensorType::kInvalid) {
    Fail(db, what + ": unknown sensor type " + std::to_string(type) +
                 " (COLMAP's are 0 camera, 1 IMU)");
  }
  if (id < 0 || id > std::numeric_limits<uint32_t>::max()) {
    Fail(db, what + ": sensor id " + std::to_string(id) + " out of range");
  }
  const SensorId sensor{*sensor_type, static_cast<uint32_t>(id)};
  if (sensor.type == SensorType::kCamera && database.cameras.count(sensor.id) == 0) {
    Fail(db, what + ": " + SensorLabel(sensor) + " is not in table cameras");
  }
  return sensor;
}

// sensor_from_rig as COLMAP stores it: 7 float64, qw qx qy qz tx ty tz; NULL: not calibrated.
std::optional<Rigid3d> SensorFromRig(const Connection& db, const Statement& row, int column,
                                     const std::string& what) {
  const BlobView blob = row.ColumnBlob(column);
  if (blob.size == 0) return std::nullopt;
  double v[7];
  if (blob.size != sizeof(v)) {
    Fail(db, what + ", sensor_from_rig: blob has " + std::to_string(blob.size) +
                 " bytes, expected 56 (qw qx qy qz tx ty tz as float64)");
  }
  std::memcpy(v, blob.data, sizeof(v));
  for (const double value : v) {
    if (!std::isfinite(value)) Fail(db, what + ", sensor_from_rig: a value is not finite");
  }
  return Rigid3d(Eigen::Quaterniond(v[0], v[1], v[2], v[3]).normalized(),
                 Eigen::Vector3d(v[4], v[5], v[6]));
}

void ReadRigs(Connection& db, FeatureDatabase* database) {
  Statement rig_row(db, "SELECT rig_id, ref_sensor_id, ref_sensor_type FROM rigs");
  while (rig_row.Step()) {
    Rig rig;
    rig.rig_id = static_cast<uint32_t>(rig_row.ColumnInt64(0));
    const std::string what = "rigs, rig " + std::to_string(rig.rig_id);
    rig.ref_sensor = CheckedSensor(db, *database, rig_row.ColumnInt64(1), rig_row.ColumnInt64(2),
                                   what + ", its reference sensor");
    database->rigs.emplace(rig.rig_id, rig);
  }
  Statement sensor_row(db,
                       "SELECT rig_id, sensor_id, sensor_type, sensor_from_rig FROM rig_sensors");
  while (sensor_row.Step()) {
    const int64_t rig_id = sensor_row.ColumnInt64(0);
    const std::string what = "rig_sensors, rig " + std::to_string(rig_id);
    const auto rig = database->rigs.find(static_cast<uint32_t>(rig_id));
    if (rig == database->rigs.end()) Fail(db, what + ": the rig is not in table rigs");
    RigSensor sensor;
    sensor.sensor =
        CheckedSensor(db, *database, sensor_row.ColumnInt64(1), sensor_row.ColumnInt64(2), what);
    sensor.sensor_from_rig = SensorFromRig(db, sensor_row, 3, what);
    rig->second.sensors.push_back(sensor);
  }
}

bool RigHasSensor(const Rig& rig, const SensorId& sensor) {
  if (rig.ref_sensor == sensor) return true;
  for (const RigSensor& other : rig.sensors) {
    if (other.sensor == sensor) return true;
  }
  return false;
}

// One frame_data row: its sensor must be one of its rig's; a camera's datum is an image of that
// camera.
FrameData CheckedFrameData(const Connection& db, const FeatureDatabase& database,
                           const Frame& frame, const Statement& row, const std::string& what) {
  FrameData data;
  data.sensor = CheckedSensor(db, database, row.ColumnInt64(2), row.ColumnInt64(3), what);
  data.data_id = static_cast<uint64_t>(row.ColumnInt64(1));
  const Rig& rig = database.rigs.at(frame.rig_id);
  if (!RigHasSensor(rig, data.sensor)) {
    Fail(db, what + ": " + SensorLabel(data.sensor) + " is not a sensor of rig " +
                 std::to_string(rig.rig_id));
  }
  if (data.sensor.type != SensorType::kCamera) return data;
  const auto image = database.images.find(static_cast<uint32_t>(data.data_id));
  if (row.ColumnInt64(1) < 0 || image == database.images.end()) {
    Fail(db, what + ": image " + std::to_string(row.ColumnInt64(1)) + " is not in table images");
  }
  if (image->second.camera_id != data.sensor.id) {
    Fail(db, what + ": image " + std::to_string(data.data_id) + " '" + image->second.name +
                 "' was taken by camera " + std::to_string(image->second.camera_id) + ", not by " +
                 SensorLabel(data.sensor));
  }
  return data;
}

void ReadFrames(Connection& db, FeatureDatabase* database) {
  Statement frame_row(db, "SELECT frame_id, rig_id FROM frames");
  while (frame_row.Step()) {
    Frame frame;
    frame.frame_id = static_cast<uint32_t>(frame_row.ColumnInt64(0));
    frame.rig_id = static_cast<uint32_t>(frame_row.ColumnInt64(1));
    if (database->rigs.count(frame.rig_id) == 0) {
      Fail(db, "frames, frame " + std::to_string(frame.frame_id) + ": rig " +
                   std::to_string(frame_row.ColumnInt64(1)) + " is not in table rigs");
    }
    database->frames.emplace(frame.frame_id, frame);
  }
  Statement data_row(db, "SELECT frame_id, data_id, sensor_id, sensor_type FROM frame_data");
  while (data_row.Step()) {
    const int64_t frame_id = data_row.ColumnInt64(0);
    const std::string what = "frame_data, frame " + std::to_string(frame_id);
    const auto frame = database->frames.find(static_cast<uint32_t>(frame_id));
    if (frame == database->frames.end()) Fail(db, what + ": the frame is not in table frames");
    frame->second.data.push_back(CheckedFrameData(db, *database, frame->second, data_row, what));
  }
}

void BindVector(Statement& statement, int index, const double* values, size_t count) {
  statement.BindBlob(index, values, count * sizeof(double));
}

// A sensor as COLMAP's tables hold it: its id at `index`, its type at `index + 1`.
void BindSensor(Statement& statement, int index, const SensorId& sensor) {
  statement.BindInt64(index, sensor.id);
  statement.BindInt64(index + 1, static_cast<int>(sensor.type));
}

}  // namespace

void ReadDatabasePosePriors(Connection& db, const DatabaseLayout& layout,
                            FeatureDatabase* database) {
  switch (layout.pose_priors) {
    case PosePriorTable::kNone:
      return;
    case PosePriorTable::kByImage:
      ReadPriorsByImage(db, layout, database);
      return;
    case PosePriorTable::kBySensorData:
      ReadPriorsBySensorData(db, layout, database);
      return;
  }
}

void ReadDatabaseRigsAndFrames(Connection& db, FeatureDatabase* database) {
  ReadRigs(db, database);
  ReadFrames(db, database);
}

Rigs RigsOrOnePerCamera(const FeatureDatabase& database) {
  if (!database.rigs.empty()) return database.rigs;
  Rigs rigs;
  for (const auto& [camera_id, camera] : database.cameras) {
    rigs.emplace(camera_id, OneCameraRig(camera_id));
  }
  return rigs;
}

Frames FramesOrOnePerImage(const FeatureDatabase& database) {
  if (!database.frames.empty()) return database.frames;
  Frames frames;
  for (const auto& [image_id, image] : database.images) {
    frames.emplace(image_id, OneImageFrame(image_id, image.camera_id));
  }
  return frames;
}

RigSummary SummarizeRigs(const FeatureDatabase& database) {
  RigSummary summary;
  summary.num_rigs = database.rigs.size();
  summary.num_frames = database.frames.size();
  for (const auto& [frame_id, frame] : database.frames) {
    size_t num_cameras = 0;
    for (const FrameData& data : frame.data) num_cameras += data.sensor.type == SensorType::kCamera;
    summary.num_multi_camera_frames += num_cameras >= 2;
    summary.max_cameras_per_frame = std::max(summary.max_cameras_per_frame, num_cameras);
  }
  return summary;
}

void WriteDatabasePosePriors(const FeatureDatabase& database, DatabaseGeneration generation,
                             Connection& db) {
  if (generation == DatabaseGeneration::kColmap38) return;
  const bool by_image = generation == DatabaseGeneration::kColmap310;
  Statement row(db, by_image ? "INSERT INTO pose_priors(image_id, position, coordinate_system, "
                               "position_covariance) VALUES(?, ?, ?, ?)"
                             : "INSERT INTO pose_priors(pose_prior_id, corr_data_id, "
                               "corr_sensor_id, corr_sensor_type, position, coordinate_system, "
                               "position_covariance, gravity) VALUES(?, ?, ?, ?, ?, ?, ?, ?)");
  // COLMAP writes an unknown covariance or gravity as NaN values (an absent blob would read as
  // zeros, a covariance of infinite weight).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix3d unknown_covariance = Eigen::Matrix3d::Constant(nan);
  const Eigen::Vector3d unknown_gravity = Eigen::Vector3d::Constant(nan);
  for (const auto& [image_id, image] : database.images) {
    if (!image.prior_translation) continue;
    const Eigen::Matrix3d& covariance =
        image.prior_position_covariance ? *image.prior_position_covariance : unknown_covariance;
    int column = 1;
    row.BindInt64(column++, image_id);
    if (!by_image) {
      row.BindInt64(column++, image_id);
      BindSensor(row, column, SensorId{SensorType::kCamera, image.camera_id});
      column += 2;
    }
    BindVector(row, column++, image.prior_translation->data(), 3);
    row.BindInt64(column++, static_cast<int>(image.prior_coordinate_system));
    BindVector(row, column++, covariance.data(), 9);
    if (!by_image) {
      BindVector(row, column++,
                 image.prior_gravity ? image.prior_gravity->data() : unknown_gravity.data(), 3);
    }
    row.Run();
  }
}

void WriteDatabaseRigsAndFrames(const FeatureDatabase& database, Connection& db) {
  Statement rig_row(db, "INSERT INTO rigs(rig_id, ref_sensor_id, ref_sensor_type) VALUES(?, ?, ?)");
  Statement sensor_row(db,
                       "INSERT INTO rig_sensors(rig_id, sensor_id, sensor_type, sensor_from_rig) "
                       "VALUES(?, ?, ?, ?)");
  for (const auto& [rig_id, rig] : RigsOrOnePerCamera(database)) {
    rig_row.BindInt64(1, rig_id);
    BindSensor(rig_row, 2, rig.ref_sensor);
    rig_row.Run();
    for (const RigSensor& sensor : rig.sensors) {
      sensor_row.BindInt64(1, rig_id);
      BindSensor(sensor_row, 2, sensor.sensor);
      if (sensor.sensor_from_rig) {
        const Rigid3d& pose = *sensor.sensor_from_rig;
        const double values[7] = {pose.rotation.w(),   pose.rotation.x(),    pose.rotation.y(),
                                  pose.rotation.z(),   pose.translation.x(), pose.translation.y(),
                                  pose.translation.z()};
        BindVector(sensor_row, 4, values, 7);
      } else {
        sensor_row.BindNull(4);
      }
      sensor_row.Run();
    }
  }
  Statement frame_row(db, "INSERT INTO frames(frame_id, rig_id) VALUES(?, ?)");
  Statement data_row(db,
                     "INSERT INTO frame_data(frame_id, data_id, sensor_id, sensor_type) "
                     "VALUES(?, ?, ?, ?)");
  for (const auto& [frame_id, frame] : FramesOrOnePerImage(database)) {
    frame_row.BindInt64(1, frame_id);
    frame_row.BindInt64(2, frame.rig_id);
    frame_row.Run();
    for (const FrameData& data : frame.data) {
      data_row.BindInt64(1, frame_id);
      data_row.BindInt64(2, static_cast<int64_t>(data.data_id));
      BindSensor(data_row, 3, data.sensor);
      data_row.Run();
    }
  }
}

}  // namespace ramap
