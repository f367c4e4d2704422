// COLMAP 4's rigs and frames files beside a model (io/colmap_model_rigs.h): written for every
// model, read back, a two-camera rig kept while the images' poses agree with it, and defects named.
#include "ramap/io/colmap_model_rigs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

Reconstruction SyntheticModel(bool two_cameras) {
  SyntheticSceneOptions options;
  options.num_images = 10;
  options.num_points = 200;
  if (two_cameras) options.second_camera = options.camera;
  return BuildSyntheticScene(options).ground_truth;
}

// Images 1, 3, 5, ... of camera 1 and 2, 4, 6, ... of camera 2 as frames of one rig, camera 2
// mounted at `camera2_from_camera1`: the even images' poses follow from the odd ones.
Reconstruction TwoCameraRigModel(const Rigid3d& camera2_from_camera1) {
  Reconstruction model = SyntheticModel(/*two_cameras=*/true);
  Rig rig;
  rig.rig_id = 1;
  rig.ref_sensor = {SensorType::kCamera, 1};
  rig.sensors.push_back({{SensorType::kCamera, 2}, camera2_from_camera1});
  model.rigs.emplace(1, rig);
  for (uint32_t id = 1; id + 1 <= 10; id += 2) {
    model.images.at(id + 1).cam_from_world =
        camera2_from_camera1 * model.images.at(id).cam_from_world;
    Frame frame;
    frame.frame_id = id;
    frame.rig_id = 1;
    frame.data = {{{SensorType::kCamera, 1}, id}, {{SensorType::kCamera, 2}, id + 1}};
    model.frames.emplace(id, frame);
  }
  return model;
}

class BothFormats : public testing::TestWithParam<ModelFormat> {};

TEST_P(BothFormats, OneRigPerCameraAndOneFramePerImage) {
  TempDir dir;
  const Reconstruction model = SyntheticModel(/*two_cameras=*/true);
  WriteColmapModel(model, dir / "model", GetParam());
  const std::string extension = GetParam() == ModelFormat::kBinary ? ".bin" : ".txt";
  EXPECT_TRUE(fs::exists(dir / ("model/rigs" + extension)));
  EXPECT_TRUE(fs::exists(dir / ("model/frames" + extension)));
  const Reconstruction read = ReadColmapModel(dir / "model");
  ASSERT_EQ(read.rigs.size(), 2u);
  EXPECT_EQ(read.rigs.at(2).ref_sensor, (SensorId{SensorType::kCamera, 2}));
  EXPECT_TRUE(read.rigs.at(2).sensors.empty());
  ASSERT_EQ(read.frames.size(), model.images.size());
  for (const auto& [image_id, image] : model.images) {
    const Frame& frame = read.frames.at(image_id);
    EXPECT_EQ(frame.rig_id, image.camera_id);
    ASSERT_EQ(frame.data.size(), 1u);
    EXPECT_EQ(frame.data[0].data_id, image_id);
    EXPECT_TRUE(frame.rig_from_world.rotation.isApprox(image.cam_from_world.rotation, 1e-15));
    EXPECT_TRUE(frame.rig_from_world.translation.isApprox(image.cam_from_world.translation));
  }
}

TEST_P(BothFormats, TwoCameraRigKeptWhileThePosesAgreeWithIt) {
  TempDir dir;
  const Rigid3d camera2_from_camera1(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
      Eigen::Vector3d(-0.5, 0.02, 0.1));
  const Reconstruction model = TwoCameraRigModel(camera2_from_camera1);
  WriteColmapModel(model, dir / "model", GetParam());
  const Reconstruction read = ReadColmapModel(dir / "model");
  ASSERT_EQ(read.rigs.size(), 1u);
  ASSERT_EQ(read.rigs.at(1).sensors.size(), 1u);
  const Rigid3d& read_pose = *read.rigs.at(1).sensors[0].sensor_from_rig;
  EXPECT_LT(read_pose.rotation.angularDistance(camera2_from_camera1.rotation), 1e-12);
  EXPECT_LT((read_pose.translation - camera2_from_camera1.translation).norm(), 1e-12);
  ASSERT_EQ(read.frames.size(), 5u);
  EXPECT_EQ(read.frames.at(3).data.size(), 2u);

  // One image moved on its own (as bundle adjustment does): the rig no longer holds, and the
  // model is written with one rig per camera so that COLMAP 4 reads the images' own poses.
  Reconstruction moved = model;
  moved.images.at(4).cam_from_world.translation.x() += 0.01;
  WriteColmapModel(moved, dir / "moved", GetParam());
  const Reconstruction read_moved = ReadColmapModel(dir / "moved");
  EXPECT_EQ(read_moved.rigs.size(), 2u);
  EXPECT_EQ(read_moved.frames.size(), 10u);
}

INSTANTIATE_TEST_SUITE_P(Formats, BothFormats,
                         testing::Values(ModelFormat::kBinary, ModelFormat::kText));

// Reading the model in `folder` fails naming each of `parts`.
void ExpectRefused(const std::string& folder, const std::vector<std::string>& parts) {
  test::ExpectInputError([&] { ReadColmapModel(folder); }, parts);
}

TEST(ColmapModelRigsBadInput, EachDefectNamed) {
  TempDir dir;
  const Reconstruction model = TwoCameraRigModel(Rigid3d());
  WriteColmapModel(model, dir / "lone", ModelFormat::kText);
  fs::remove(dir / "lone/rigs.txt");
  ExpectRefused(dir / "lone", {"rigs.txt", "file not found", "frames.txt"});

  WriteColmapModel(model, dir / "sensor", ModelFormat::kText);
  {
    std::ofstream frames(dir / "sensor/frames.txt");
    frames << "1 1 1 0 0 0 0 0 0 1 CAMERA 7 1\n";
  }
  ExpectRefused(dir / "sensor", {"frames.txt", "frame 1", "camera 7 is not a sensor of rig 1"});

  WriteColmapModel(model, dir / "type", ModelFormat::kText);
  {
    std::ofstream rigs(dir / "type/rigs.txt");
    rigs << "1 2 CAMERA 1 LIDAR 2 0\n";
  }
  ExpectRefused(dir / "type", {"rigs.txt", "line 1", "unknown sensor type 'LIDAR'"});

  WriteColmapModel(model, dir / "truncated", ModelFormat::kBinary);
  fs::resize_file(dir / "truncated/frames.bin", 30);
  ExpectRefused(dir / "truncated", {"frames.bin", "truncated while reading frame 1"});
}

}  // namespace
}  // namespace ramap
