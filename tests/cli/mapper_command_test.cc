// `ramap mapper` as a user runs it: the model it writes is one that COLMAP's own tools open, refine
// and compare; a database it cannot use ends in a message and leaves no output behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ramap/io/colmap_model.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

void Synthesize(const test::TempDir& dir) {
  const test::CommandResult result = test::RunCommand(
      test::RamapCommand() + "synthesize --output_path '" + (dir / "scene") +
      "' --Synthetic.path circle --Synthetic.num_images 16 --Synthetic.num_points 1500"
      " --Synthetic.pixel_noise 0.5 --Synthetic.seed 9");
  ASSERT_EQ(result.exit_code, 0) << result.output;
}

// `ramap mapper` on the synthesized scene's database into dir/sparse, with `options`.
test::CommandResult MapScene(const test::TempDir& dir, const std::string& options) {
  return test::RunCommand(test::RamapCommand() + "mapper --database_path '" +
                          (dir / "scene/database.db") + "' --output_path '" + (dir / "sparse") +
                          "' " + options);
}

TEST(MapperCommand, ColmapToolsOpenRefineAndCompareTheModel) {
  RAMAP_REQUIRE_COLMAP();
  test::TempDir dir;
  Synthesize(dir);
  const std::string db = dir / "scene/database.db";
  const test::CommandResult mapper =
      test::RunCommand(test::RamapCommand() + "mapper --database_path '" + db +
                       "' --output_path '" + (dir / "sparse") + "'");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  EXPECT_NE(mapper.output.find("16 of 16 images registered"), std::string::npos) << mapper.output;
  EXPECT_TRUE(fs::exists(dir / "sparse/0/trajectory_tum.txt"));
  std::ifstream summary_file(dir / "sparse/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["num_registered_images"], 16);

  const test::CommandResult analyzer =
      test::RunCommand("colmap model_analyzer --path '" + (dir / "sparse/0") + "'");
  ASSERT_EQ(analyzer.exit_code, 0) << analyzer.output;
  EXPECT_NE(analyzer.output.find("Registered images: 16"), std::string::npos) << analyzer.output;

  fs::create_directories(dir / "ba");
  const test::CommandResult ba = test::RunCommand(
      "colmap bundle_adjuster --input_path '" + (dir / "sparse/0") + "' --output_path '" +
      (dir / "ba") +
      "' --BundleAdjustment.refine_focal_length 0"
      " --BundleAdjustment.refine_principal_point 0 --BundleAdjustment.refine_extra_params 0");
  ASSERT_EQ(ba.exit_code, 0) << ba.output;
  EXPECT_EQ(ReadColmapModel(dir / "ba").images.size(), 16u);

  fs::create_directories(dir / "images");
  fs::create_directories(dir / "triangulated");
  const test::CommandResult triangulator = test::RunCommand(
      "colmap point_triangulator --database_path '" + db + "' --image_path '" + (dir / "images") +
      "' --input_path '" + (dir / "sparse/0") + "' --output_path '" + (dir / "triangulated") +
      "' --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0"
      " --Mapper.ba_refine_extra_params 0");
  ASSERT_EQ(triangulator.exit_code, 0) << triangulator.output;
  EXPECT_GT(ReadColmapModel(dir / "triangulated").points3D.size(), 1000u);

  const test::CommandResult comparer =
      test::RunCommand("colmap model_comparer --input_path1 '" + (dir / "sparse/0") +
                       "' --input_path2 '" + (dir / "scene/ground_truth") + "'");
  ASSERT_EQ(comparer.exit_code, 0) << comparer.output;
}

// summary.json says where rotation averaging's time went, phase by phase, and how many
// factorisations it took.
TEST(MapperCommand, SummaryReportsRotationAveragingPhases) {
  test::TempDir dir;
  Synthesize(dir);
  const test::CommandResult mapper = MapScene(dir, "--Mapper.refine 0");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  std::ifstream summary_file(dir / "sparse/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json& rotations = summary["components"][0]["rotation_averaging"];
  EXPECT_GE(rotations["num_factorizations"].get<int>(), 1);
  const nlohmann::json& seconds = rotations["seconds"];
  double parts = 0;
  for (const char* phase : {"windows", "init", "l1", "irls", "pruning", "certificate"}) {
    ASSERT_TRUE(seconds.contains(phase)) << phase;
    EXPECT_GE(seconds[phase].get<double>(), 0.0) << phase;
    parts += seconds[phase].get<double>();
  }
  EXPECT_GT(seconds["l1"].get<double>(), 0.0);
  EXPECT_LE(parts, seconds["total"].get<double>() * 1.001 + 1e-6);
  EXPECT_LE(seconds["total"].get<double>(),
            summary["stage_seconds"]["rotation averaging"].get<double>() * 1.001 + 1e-6);
}

TEST(MapperCommand, TextOutputOnRequest) {
  test::TempDir dir;
  Synthesize(dir);
  const test::CommandResult mapper = MapScene(dir, "--output_type TXT");
  ASSERT_EQ(mapper.exit_code, 0) << mapper.output;
  EXPECT_TRUE(fs::exists(dir / "sparse/0/images.txt"));
  EXPECT_FALSE(fs::exists(dir / "sparse/0/images.bin"));
  EXPECT_EQ(ReadColmapModel(dir / "sparse/0").images.size(), 16u);
}

TEST(MapperCommand, UnusableDatabaseLeavesNoOutput) {
  test::TempDir dir;
  Synthesize(dir);
  const std::string db = dir / "scene/database.db";
  ASSERT_EQ(test::RunCommand("sqlite3 '" + db + "' 'DELETE FROM two_view_geometries;'").exit_code,
            0);
  const test::CommandResult mapper =
      test::RunCommand(test::RamapCommand() + "mapper --database_path '" + db +
                       "' --output_path '" + (dir / "sparse") + "'");
  EXPECT_EQ(mapper.exit_code, 2) << mapper.output;
  EXPECT_NE(mapper.output.find(db), std::string::npos) << mapper.output;
  EXPECT_NE(mapper.output.find("no image pair has verified matches"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "sparse"));
}

}  // namespace
}  // namespace ramap
