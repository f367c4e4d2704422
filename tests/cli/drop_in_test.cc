// ramap in place of the `colmap` executable: the command lines nerfstudio's ns-process-data and
// 3D Gaussian Splatting's convert.py issue, word for word with `ramap` as the executable, run on a
// synthetic scene and on generated images (scripts/drop_in.sh runs them on real data).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

test::CommandResult RunRamap(const std::string& arguments) {
  return test::RunCommand(test::RamapCommand() + arguments + " 2>&1");
}

void ExpectSucceeds(const test::CommandResult& result, const std::string& note = "") {
  EXPECT_EQ(result.exit_code, 0) << result.output;
  if (!note.empty()) {
    EXPECT_NE(result.output.find(note), std::string::npos) << result.output;
  }
}

// The mapper, bundle_adjuster and model_aligner lines of both tools on a synthetic database.
TEST(DropIn, MapperBundleAdjusterAndAlignerLines) {
  test::TempDir dir;
  const std::string d = dir.path();
  ExpectSucceeds(
      RunRamap("synthesize --output_path " + d +
               "/scene --Synthetic.path circle "
               "--Synthetic.num_images 10 --Synthetic.num_points 800 --Synthetic.seed 4"));
  fs::create_directories(d + "/sparse");
  // nerfstudio (COLMAP >= 3.7) and convert.py.
  ExpectSucceeds(
      RunRamap("mapper --database_path " + d + "/scene/database.db --image_path " + d +
               "/scene --output_path " + d + "/sparse --Mapper.ba_global_function_tolerance=1e-6"),
      "--Mapper.ba_global_function_tolerance read as --BundleAdjustment.function_tolerance");
  ExpectSucceeds(RunRamap("bundle_adjuster --input_path " + d + "/sparse/0 --output_path " + d +
                          "/sparse/0 --BundleAdjustment.refine_principal_point 1"));
  const std::string trajectory_before = test::ReadFileBytes(d + "/sparse/0/trajectory_tum.txt");
  ExpectSucceeds(RunRamap("model_aligner --input_path " + d + "/sparse/0 --database_path " + d +
                          "/scene/database.db --alignment_max_error  0.1 --alignment_type  plane "
                          "--output_path " +
                          d + "/sparse/0"));
  const Reconstruction model = ReadColmapModel(d + "/sparse/0");
  EXPECT_EQ(model.images.size(), 10u);
  // The mapper's trajectory beside the model follows it to the new frame.
  EXPECT_NE(test::ReadFileBytes(d + "/sparse/0/trajectory_tum.txt"), trajectory_before);
  EXPECT_EQ(model.rigs.size(), model.cameras.size());
  // Upright on the principal plane: the points spread least along z, and are centred there.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), spread = Eigen::Vector3d::Zero();
  for (const auto& [id, point] : model.points3D) mean += point.xyz;
  mean /= model.points3D.size();
  for (const auto& [id, point] : model.points3D) spread += (point.xyz - mean).cwiseAbs2();
  EXPECT_LT(std::abs(mean.z()), 1e-6 * std::sqrt(spread.sum()));
  EXPECT_LT(spread.z(), spread.y());
  EXPECT_LT(spread.y(), spread.x());

  // An option ramap does not know still fails, by name.
  const test::CommandResult unknown =
      RunRamap("mapper --database_path " + d + "/scene/database.db --output_path " + d +
               "/other --Mapper.ba_local_max_refinements 2");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--Mapper.ba_local_max_refinements"), std::string::npos);
}

// Generated images of one textured plane seen from a few positions.
void WriteImages(const std::string& folder) {
  fs::create_directories(folder);
  std::mt19937 random(9);
  cv::Mat texture(600, 800, CV_8U);
  cv::randu(texture, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.5);
  for (int k = 0; k < 4; ++k) {
    const cv::Mat view = texture(cv::Rect(40 * k, 20 * k, 480, 360)).clone();
    cv::imwrite(folder + "/view" + std::to_string(k) + ".png", view);
  }
}

// The feature_extractor and exhaustive_matcher lines, with the GPU asked for and COLMAP's
// OPENCV camera.
TEST(DropIn, ExtractorAndMatcherLines) {
  test::TempDir dir;
  const std::string d = dir.path();
  WriteImages(d + "/input");
  fs::create_directories(d + "/distorted");
  ExpectSucceeds(RunRamap("feature_extractor --database_path " + d +
                          "/distorted/database.db "
                          "--image_path " +
                          d +
                          "/input --ImageReader.single_camera 1 "
                          "--ImageReader.camera_model OPENCV --SiftExtraction.use_gpu 1"),
                 "--SiftExtraction.use_gpu 1 ignored: ramap runs on the CPU");
  ExpectSucceeds(RunRamap("exhaustive_matcher --database_path " + d +
                          "/distorted/database.db --SiftMatching.use_gpu 1"),
                 "--SiftMatching.use_gpu 1 ignored");
  ExpectSucceeds(RunRamap("sequential_matcher --database_path " + d +
                          "/distorted/database.db --FeatureMatching.use_gpu 0 "
                          "--SequentialMatching.overlap 2"),
                 "--SequentialMatching.overlap read as --Matching.overlap");
  // nerfstudio's default matching, with the tree it downloads.
  ExpectSucceeds(RunRamap("vocab_tree_matcher --database_path " + d +
                          "/distorted/database.db --SiftMatching.use_gpu 1 "
                          "--VocabTreeMatching.vocab_tree_path " +
                          d + "/vocab_tree.fbow --VocabTreeMatching.num_images 2"),
                 "--VocabTreeMatching.num_images read as --Matching.retrieval_num_neighbors");
  const FeatureDatabase database = ReadColmapDatabase(d + "/distorted/database.db");
  ASSERT_EQ(database.cameras.size(), 1u);
  EXPECT_EQ(database.cameras.begin()->second.model, CameraModel::kOpenCV);
  EXPECT_EQ(database.images.size(), 4u);
  EXPECT_FALSE(database.two_view_geometries.empty());
}

}  // namespace
}  // namespace ramap
