// `ramap synthesize --output_path DIR [--Synthetic.* ...]`: a synthetic scene with exact ground
// truth, written as DIR/database.db (COLMAP database), DIR/ground_truth (COLMAP model) and
// DIR/ground_truth.txt (TUM trajectory), so that the mapper, COLMAP and evaluation tools can be
// run on data whose answer is known.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>

#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"
#include "synthetic_options.h"

namespace ramap::cli {

namespace {

// The database, the ground-truth model and its TUM trajectory in `output_path`.
void WriteScene(const SyntheticScene& scene, const std::string& output_path, ModelFormat format,
                DatabaseGeneration generation) {
  std::error_code error;
  std::filesystem::create_directories(output_path, error);
  if (error) throw InputError(output_path, "cannot create the folder: " + error.message());
  WriteColmapDatabase(scene.database, output_path + "/database.db", generation);
  WriteColmapModel(scene.ground_truth, output_path + "/ground_truth", format);
  WriteTumTrajectory(scene.ground_truth, output_path + "/ground_truth.txt");
}

void PrintScene(const SyntheticScene& scene, const std::string& output_path, std::ostream& out) {
  const DatabaseCounts counts = CountDatabase(scene.database);
  out << "Synthetic scene in " << output_path << ": " << scene.ground_truth.images.size()
      << " images, " << scene.ground_truth.points3D.size() << " points3D, "
      << scene.database.two_view_geometries.size() << " verified pairs ("
      << scene.outlier_pair_ids.size() << " outlier pairs, " << scene.aliased_pair_ids.size()
      << " aliased pairs), " << counts.num_matches << " matches, " << counts.num_inliers
      << " inliers\n";
}

}  // namespace

int RunSynthesize(int argc, char** argv) {
  CLI::App app(
      "Builds a synthetic scene with exact ground truth: a COLMAP database (keypoints, matches "
      "with outliers, verified two-view geometries), the true COLMAP model and a TUM trajectory.",
      "ramap synthesize");
  SyntheticSceneOptions options;
  SceneOptionText text;
  std::string output_path;
  std::string output_type = "BIN";
  app.add_option("--output_path", output_path,
                 "folder for database.db, ground_truth/ and ground_truth.txt (created)")
      ->required();
  AddSceneOptions(app, &options, &text);
  app.add_option("--output_type", output_type, "ground-truth model format")
      ->check(CLI::IsMember({"BIN", "TXT"}))
      ->capture_default_str();
  std::string generation_name = "3.8";
  app.add_option("--Database.generation", generation_name,
                 "schema of the database: 3.8 (every COLMAP reads it) | 3.10 | 4 (3.12-4.x)")
      ->capture_default_str();
  bool with_descriptors = false;
  SyntheticDescriptorOptions descriptor_options;
  app.add_option("--Synthetic.descriptors", with_descriptors,
                 "1: SIFT-like descriptors for every keypoint (one per 3D point, noisy per view), "
                 "so that ramap matcher can match the database again")
      ->capture_default_str();
  app.add_option("--Synthetic.descriptor_noise", descriptor_options.noise_sigma,
                 "noise of a view's descriptor values (SIFT's scale: norm 512)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  if (const auto exit_code = ParseOptions(app, argc, argv)) return *exit_code;
  const DatabaseGeneration generation =
      DatabaseGenerationFromName(generation_name, "--Database.generation");
  FinishSceneOptions(text, app.count("--Synthetic.num_images") > 0, &options);
  CheckFolderOutput("--output_path", output_path, {text.trajectory_path});
  CheckNewDatabasePath("--output_path", output_path + "/database.db", {text.trajectory_path});

  SyntheticScene scene = BuildSyntheticScene(options);
  if (with_descriptors) {
    descriptor_options.seed = options.seed;
    AddSyntheticDescriptors(descriptor_options, &scene);
  }
  // Removed again if writing fails or is interrupted.
  CreatedOutput created(output_path);
  CreatedOutput created_database(output_path + "/database.db");
  WriteScene(scene, output_path, output_type == "TXT" ? ModelFormat::kText : ModelFormat::kBinary,
             generation);
  created_database.Keep();
  created.Keep();
  PrintScene(scene, output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
