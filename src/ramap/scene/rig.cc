#include "ramap/scene/rig.h"

#include <array>
#include <utility>

namespace ramap {
namespace {

constexpr std::array<std::pair<SensorType, const char*>, 3> kSensorTypes = {{
    {SensorType::kInvalid, "INVALID"},
    {SensorType::kCamera, "CAMERA"},
    {SensorType::kImu, "IMU"},
}};

}  // namespace

std::string SensorTypeName(SensorType type) {
  for (const auto& [known, name] : kSensorTypes) {
    if (known == type) return name;
  }
  return "";
}

std::optional<SensorType> SensorTypeFromName(const std::string& name) {
  for (const auto& [type, known] : kSensorTypes) {
    if (name == known) return type;
  }
  return std::nullopt;
}

std::optional<SensorType> SensorTypeFromId(int64_t id) {
  for (const auto& [type, name] : kSensorTypes) {
    if (static_cast<int64_t>(type) == id) return type;
  }
  return std::nullopt;
}

std::string SensorLabel(const SensorId& sensor) {
  const std::string name = SensorTypeName(sensor.type);
  const std::string kind = sensor.type == SensorType::kCamera ? "camera" : name;
  return (kind.empty() ? "sensor of type " + std::to_string(static_cast<int>(sensor.type)) : kind) +
         " " + std::to_string(sensor.id);
}

Rig OneCameraRig(uint32_t camera_id) {
  Rig rig;
  rig.rig_id = camera_id;
  rig.ref_sensor = SensorId{SensorType::kCamera, camera_id};
  return rig;
}

Frame OneImageFrame(uint32_t image_id, uint32_t camera_id) {
  Frame frame;
  frame.frame_id = image_id;
  frame.rig_id = camera_id;
  frame.data.push_back(FrameData{SensorId{SensorType::kCamera, camera_id}, image_id});
  return frame;
}

}  // namespace ramap
