// Rigs and frames: COLMAP 4's grouping of images (from 3.12 on, in its databases and models).
//
// A rig is a set of sensors mounted together: one reference sensor, whose frame is the rig's,
// and others with their pose in the rig (sensor_from_rig, unknown until calibrated). A frame is
// one instant of a rig: the data each sensor took then (for a camera, an image id) and, in a
// model, the rig's pose rig_from_world. An image's pose is then sensor_from_rig * rig_from_world.
//
// A database or model without rigs has, as COLMAP 4 reads it, one rig per camera (rig id = camera
// id, the camera its reference sensor) and one frame per image (frame id = image id): the
// "trivial" rigs ramap writes where it was given none.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "ramap/scene/rigid3.h"

namespace ramap {

// COLMAP's SensorType, with its integer values.
enum class SensorType : int { kInvalid = -1, kCamera = 0, kImu = 1 };

// "CAMERA", "IMU", "INVALID" (COLMAP's names, used in its text models); empty for other values.
std::string SensorTypeName(SensorType type);
std::optional<SensorType> SensorTypeFromName(const std::string& name);
std::optional<SensorType> SensorTypeFromId(int64_t id);

struct SensorId {
  SensorType type = SensorType::kCamera;
  uint32_t id = 0;  // for a camera, its camera id

  bool operator<(const SensorId& other) const {
    return std::tie(type, id) < std::tie(other.type, other.id);
  }
  bool operator==(const SensorId& other) const { return type == other.type && id == other.id; }
};

// "camera 3", "IMU 2": for messages.
std::string SensorLabel(const SensorId& sensor);

struct RigSensor {
  SensorId sensor;
  std::optional<Rigid3d> sensor_from_rig;  // empty: not calibrated
};

struct Rig {
  uint32_t rig_id = 0;
  SensorId ref_sensor;
  std::vector<RigSensor> sensors;  // the other sensors, without the reference

  size_t num_sensors() const { return 1 + sensors.size(); }
};

// One sensor's datum in a frame; for a camera, data_id is the image id.
struct FrameData {
  SensorId sensor;
  uint64_t data_id = 0;
};

struct Frame {
  uint32_t frame_id = 0;
  uint32_t rig_id = 0;
  Rigid3d rig_from_world;  // held by models only; identity in a database
  std::vector<FrameData> data;
};

using Rigs = std::map<uint32_t, Rig>;
using Frames = std::map<uint32_t, Frame>;

// The trivial rig of a camera (rig id = camera id, the camera its only sensor) and the frame of one
// image in it (frame id = image id): what COLMAP 4 makes where it was given no rigs.
Rig OneCameraRig(uint32_t camera_id);
Frame OneImageFrame(uint32_t image_id, uint32_t camera_id);

}  // namespace ramap
