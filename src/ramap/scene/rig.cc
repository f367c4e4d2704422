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

}  // namespace ramap
