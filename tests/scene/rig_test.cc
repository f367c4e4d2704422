// Rig sensors by COLMAP's type names and ids, their labels in messages, and the trivial rig and
// frame COLMAP 4 makes of a camera and an image.
#include "ramap/scene/rig.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

TEST(Rig, SensorTypesByColmapsNamesAndIds) {
  const std::vector<std::tuple<SensorType, std::string, int>> types = {
      {SensorType::kInvalid, "INVALID", -1},
      {SensorType::kCamera, "CAMERA", 0},
      {SensorType::kImu, "IMU", 1}};
  for (const auto& [type, name, id] : types) {
    EXPECT_EQ(SensorTypeName(type), name);
    EXPECT_EQ(SensorTypeFromName(name), type);
    EXPECT_EQ(SensorTypeFromId(id), type);
  }
  EXPECT_EQ(SensorTypeName(static_cast<SensorType>(7)), "");
  EXPECT_FALSE(SensorTypeFromName("camera").has_value());
  EXPECT_FALSE(SensorTypeFromId(2).has_value());
}

TEST(Rig, SensorLabelsForMessages) {
  EXPECT_EQ(SensorLabel({SensorType::kCamera, 3}), "camera 3");
  EXPECT_EQ(SensorLabel({SensorType::kImu, 2}), "IMU 2");
  EXPECT_EQ(SensorLabel({static_cast<SensorType>(7), 5}), "sensor of type 7 5");
}

TEST(Rig, TrivialRigAndFrameOfACameraAndAnImage) {
  const Rig rig = OneCameraRig(4);
  EXPECT_EQ(rig.rig_id, 4u);
  EXPECT_EQ(rig.ref_sensor, (SensorId{SensorType::kCamera, 4}));
  EXPECT_TRUE(rig.sensors.empty());
  EXPECT_EQ(rig.num_sensors(), 1u);
  const Frame frame = OneImageFrame(17, 4);
  EXPECT_EQ(frame.frame_id, 17u);
  EXPECT_EQ(frame.rig_id, 4u);
  ASSERT_EQ(frame.data.size(), 1u);
  EXPECT_EQ(frame.data[0].sensor, (SensorId{SensorType::kCamera, 4}));
  EXPECT_EQ(frame.data[0].data_id, 17u);
}

}  // namespace
}  // namespace ramap
