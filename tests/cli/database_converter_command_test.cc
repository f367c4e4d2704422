// `ramap database_converter`: a database rewritten as each other generation and read back with
// everything the target holds (images, cameras, priors, keypoints, descriptors, matches, verified
// geometries); an existing output and a generation no COLMAP has are refused, nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <tuple>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A small line with descriptors, a second camera, and Cartesian priors on every other image.
FeatureDatabase Scene() {
  SyntheticSceneOptions options;
  options.num_images = 6;
  options.num_points = 200;
  options.keypoint_columns = 4;
  options.second_camera = options.camera;
  options.second_camera->params[0] = 520;
  SyntheticScene scene = BuildSyntheticScene(options);
  AddSyntheticDescriptors(SyntheticDescriptorOptions(), &scene);
  for (auto& [id, image] : scene.database.images) {
    if (id % 2 == 1) continue;
    image.prior_translation = Eigen::Vector3d(id, -2.5 * id, 0.125);
    image.prior_coordinate_system = PriorCoordinateSystem::kCartesian;
  }
  return scene.database;
}

FeatureDatabase Read(const std::string& path) {
  DatabaseReadOptions everything;
  everything.read_descriptors = true;
  return ReadColmapDatabase(path, everything);
}

void ExpectSameContents(const FeatureDatabase& expected, const FeatureDatabase& read) {
  ASSERT_EQ(read.cameras.size(), expected.cameras.size());
  for (const auto& [id, camera] : expected.cameras) {
    EXPECT_EQ(read.cameras.at(id).params, camera.params) << "camera " << id;
  }
  ASSERT_EQ(read.images.size(), expected.images.size());
  for (const auto& [id, image] : expected.images) {
    const Image& got = read.images.at(id);
    EXPECT_EQ(got.name, image.name);
    EXPECT_EQ(got.camera_id, image.camera_id);
    ASSERT_EQ(got.prior_translation.has_value(), image.prior_translation.has_value()) << id;
    if (image.prior_translation) EXPECT_EQ(*got.prior_translation, *image.prior_translation);
    EXPECT_EQ(read.keypoints.at(id).num_cols, expected.keypoints.at(id).num_cols);
    EXPECT_EQ(read.keypoints.at(id).data, expected.keypoints.at(id).data) << id;
    EXPECT_EQ(read.descriptors.at(id).data, expected.descriptors.at(id).data) << id;
  }
  ASSERT_EQ(read.matches.size(), expected.matches.size());
  for (const auto& [pair_id, matches] : expected.matches) {
    EXPECT_EQ(read.matches.at(pair_id).size(), matches.size());
  }
  ASSERT_EQ(read.two_view_geometries.size(), expected.two_view_geometries.size());
  for (const auto& [pair_id, geometry] : expected.two_view_geometries) {
    const TwoViewGeometry& got = read.two_view_geometries.at(pair_id);
    EXPECT_EQ(got.config, geometry.config);
    ASSERT_EQ(got.inlier_matches.size(), geometry.inlier_matches.size());
    for (size_t k = 0; k < geometry.inlier_matches.size(); ++k) {
      EXPECT_EQ(got.inlier_matches[k].point2D_idx1, geometry.inlier_matches[k].point2D_idx1);
      EXPECT_EQ(got.inlier_matches[k].point2D_idx2, geometry.inlier_matches[k].point2D_idx2);
    }
    EXPECT_EQ(got.E, geometry.E);
  }
}

std::string Convert(const std::string& from, const std::string& to, const std::string& generation) {
  return test::RamapCommand() + "database_converter --database_path '" + from +
         "' --output_path '" + to + "' --Database.generation " + generation;
}

TEST(DatabaseConverterCommand, EachGenerationConvertedAndReadBack) {
  test::TempDir dir;
  const FeatureDatabase scene = Scene();
  WriteColmapDatabase(scene, dir / "38.db", DatabaseGeneration::kColmap38);
  // 3.8 -> 4 -> 3.10 -> 3.8, each read back whole.
  const std::vector<std::tuple<std::string, std::string, std::string, DatabaseGeneration>> steps = {
      {"38.db", "4.db", "4.1.1", DatabaseGeneration::kColmap4},
      {"4.db", "310.db", "3.11", DatabaseGeneration::kColmap310},
      {"310.db", "back.db", "3.8", DatabaseGeneration::kColmap38}};
  for (const auto& [from, to, name, generation] : steps) {
    SCOPED_TRACE(from + " -> " + to);
    const test::CommandResult result = test::RunCommand(Convert(dir / from, dir / to, name));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("Wrote " + (dir / to) + " (" +
                                 DatabaseGenerationLabel(generation) + ", from "),
              std::string::npos)
        << result.output;
    const FeatureDatabase read = Read(dir / to);
    EXPECT_EQ(read.generation, generation);
    ExpectSameContents(scene, read);
  }
  // A 4.x database gets COLMAP 4's trivial rigs and frames: one per camera, one per image.
  const FeatureDatabase four = Read(dir / "4.db");
  EXPECT_EQ(four.rigs.size(), 2u);
  EXPECT_EQ(four.frames.size(), 6u);
}

TEST(DatabaseConverterCommand, AnExistingOutputOrAnUnknownGenerationIsRefused) {
  test::TempDir dir;
  WriteColmapDatabase(Scene(), dir / "38.db", DatabaseGeneration::kColmap38);
  WriteColmapDatabase(Scene(), dir / "existing.db", DatabaseGeneration::kColmap4);
  const std::string before = test::ReadFileBytes(dir / "existing.db");
  const test::CommandResult existing =
      test::RunCommand(Convert(dir / "38.db", dir / "existing.db", "4"));
  EXPECT_EQ(existing.exit_code, 2) << existing.output;
  EXPECT_NE(existing.output.find("--output_path"), std::string::npos) << existing.output;
  EXPECT_EQ(test::ReadFileBytes(dir / "existing.db"), before);

  const test::CommandResult unknown = test::RunCommand(Convert(dir / "38.db", dir / "new.db", "5"));
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--Database.generation"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("'5'"), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(dir / "new.db"));
  // Onto its own input.
  const test::CommandResult itself = test::RunCommand(Convert(dir / "38.db", dir / "38.db", "4"));
  EXPECT_EQ(itself.exit_code, 2) << itself.output;
  EXPECT_NE(itself.output.find("--output_path"), std::string::npos) << itself.output;
}

}  // namespace
}  // namespace ramap
