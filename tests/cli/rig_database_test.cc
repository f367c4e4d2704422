// A 4.x database whose frames hold the images of a two-camera rig: `ramap mapper` maps every image
// on its own, and says so in its log and in summary.json.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "ramap/io/colmap_database.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(RigDatabase, MapperAveragesEachImageAndSaysSo) {
  test::TempDir dir;
  SyntheticSceneOptions options;
  options.layout = SyntheticLayout::kSequential;
  options.path = SyntheticPath::kCircle;
  options.num_images = 12;
  options.num_points = 800;
  options.second_camera = options.camera;  // even images: camera 2
  FeatureDatabase database = BuildSyntheticScene(options).database;
  Rig rig;
  rig.rig_id = 1;
  rig.ref_sensor = {SensorType::kCamera, 1};
  rig.sensors.push_back({{SensorType::kCamera, 2}, std::nullopt});
  database.rigs.emplace(1, rig);
  for (uint32_t id = 1; id < 12; id += 2) {
    Frame frame;
    frame.frame_id = id;
    frame.rig_id = 1;
    frame.data = {{{SensorType::kCamera, 1}, id}, {{SensorType::kCamera, 2}, id + 1}};
    database.frames.emplace(id, frame);
  }
  WriteColmapDatabase(database, dir / "db.db", DatabaseGeneration::kColmap4);

  const test::CommandResult result =
      test::RunCommand("'" + test::RamapBinary() + "' mapper --database_path '" + (dir / "db.db") +
                       "' --output_path '" + (dir / "sparse") + "' 2>&1");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("6 of 6 frames hold images of up to 2 cameras"), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("COLMAP 3.12-4.x"), std::string::npos);
  std::ifstream summary_file(dir / "sparse/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json& read = summary.at("run").at("database");
  EXPECT_EQ(read.at("num_multi_camera_frames"), 6);
  EXPECT_EQ(read.at("rig_constraints_used"), false);
}

}  // namespace
}  // namespace ramap
