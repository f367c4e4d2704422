// `ramap synthesize --output_path DIR [--Synthetic.* ...]`: a synthetic scene with exact ground
// truth, written as DIR/database.db (COLMAP database), DIR/ground_truth (COLMAP model) and
// DIR/ground_truth.txt (TUM trajectory), so that the mapper, COLMAP and evaluation tools can be
// run on data whose answer is known.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include "options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap::cli {

namespace {

// The database, the ground-truth model and its TUM trajectory in `output_path`.
void WriteScene(const SyntheticScene& scene, const std::string& output_path, ModelFormat format) {
  std::error_code error;
  std::filesystem::create_directories(output_path, error);
  if (error) throw InputError(output_path, "cannot create the folder: " + error.message());
  WriteColmapDatabase(scene.database, output_path + "/database.db");
  WriteColmapModel(scene.ground_truth, output_path + "/ground_truth", format);
  WriteTumTrajectory(scene.ground_truth, output_path + "/ground_truth.txt");
}

void PrintScene(const SyntheticScene& scene, const std::string& output_path, std::ostream& out) {
  size_t num_matches = 0;
  for (const auto& [pair_id, matches] : scene.database.matches) num_matches += matches.size();
  size_t num_inliers = 0;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    num_inliers += geometry.inlier_matches.size();
  }
  out << "Synthetic scene in " << output_path << ": " << scene.ground_truth.images.size()
      << " images, " << scene.ground_truth.points3D.size() << " points3D, "
      << scene.database.two_view_geometries.size() << " verified pairs ("
      << scene.outlier_pair_ids.size() << " outlier pairs), " << num_matches << " matches, "
      << num_inliers << " inliers\n";
}

// The options given as text, converted once parsing is done.
struct SceneOptionText {
  std::string layout = "sequential";
  std::string path = "line";
  std::string trajectory_path;
  std::string camera_model;
  std::string camera_params = "500,500,320,240";
};

void AddSceneOptions(CLI::App& app, SyntheticSceneOptions* options, SceneOptionText* text) {
  app.add_option("--Synthetic.layout", text->layout,
                 "sequential (a path) or unordered (around an object)")
      ->check(CLI::IsMember({"sequential", "unordered"}))
      ->capture_default_str();
  app.add_option("--Synthetic.path", text->path,
                 "sequential path: line (forward motion), circle (orbit of an object), loop (a "
                 "closed drive)")
      ->check(CLI::IsMember({"line", "circle", "loop"}))
      ->capture_default_str();
  app.add_option("--Synthetic.trajectory_path", text->trajectory_path,
                 "KITTI odometry pose file whose poses the sequential cameras take (instead of "
                 "--Synthetic.path); --Synthetic.num_images 0 takes all")
      ->check(CLI::ExistingFile);
  app.add_option("--Synthetic.num_images", options->num_images, "number of images")
      ->capture_default_str();
  app.add_option("--Synthetic.num_points", options->num_points, "number of random 3D points")
      ->capture_default_str();
  app.add_option("--Synthetic.pixel_noise", options->pixel_noise_sigma,
                 "standard deviation of keypoint noise, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.outlier_ratio", options->outlier_ratio,
                 "fraction of each pair's raw matches that are wrong")
      ->capture_default_str();
  app.add_option("--Synthetic.num_outlier_pairs", options->num_outlier_pairs,
                 "pairs with only wrong matches and a wrong verified geometry")
      ->capture_default_str();
  app.add_option("--Synthetic.overlap", options->overlap,
                 "sequential: match each image with its next N images")
      ->capture_default_str();
  app.add_option("--Synthetic.min_num_inliers", options->min_num_inliers,
                 "fewest true matches of a pair with a two-view geometry")
      ->capture_default_str();
  app.add_option("--Synthetic.min_shared_points", options->min_shared_points,
                 "unordered: fewest shared points of a matched pair")
      ->capture_default_str();
  app.add_option("--Synthetic.step_length", options->step_length,
                 "generated paths: distance between frames")
      ->capture_default_str();
  app.add_option("--Synthetic.min_depth", options->min_depth, "nearest point depth")
      ->capture_default_str();
  app.add_option("--Synthetic.max_depth", options->max_depth, "farthest point depth")
      ->capture_default_str();
  text->camera_model = CameraModelName(options->camera.model);
  app.add_option("--Synthetic.camera_model", text->camera_model, "COLMAP camera model name")
      ->capture_default_str();
  app.add_option("--Synthetic.camera_params", text->camera_params,
                 "camera parameters in COLMAP's order, comma-separated")
      ->capture_default_str();
  app.add_option("--Synthetic.width", options->camera.width, "image width, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.height", options->camera.height, "image height, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.seed", options->seed, "random seed (same seed, same scene)")
      ->capture_default_str();
}

// Converts the text options into `options` and checks them. A trajectory file replaces the
// generated path; without --Synthetic.num_images (`num_images_given`) all its poses are taken.
void FinishSceneOptions(const SceneOptionText& text, bool num_images_given,
                        SyntheticSceneOptions* options) {
  options->layout =
      text.layout == "unordered" ? SyntheticLayout::kUnordered : SyntheticLayout::kSequential;
  const std::map<std::string, SyntheticPath> paths = {{"line", SyntheticPath::kLine},
                                                      {"circle", SyntheticPath::kCircle},
                                                      {"loop", SyntheticPath::kLoop}};
  options->path = paths.at(text.path);
  const std::optional<CameraModel> model = CameraModelFromName(text.camera_model);
  if (!model) {
    throw InputError("--Synthetic.camera_model", "unknown model '" + text.camera_model + "'");
  }
  options->camera.model = *model;
  options->camera.params = ParseCameraParams(text.camera_params, "--Synthetic.camera_params");
  if (!text.trajectory_path.empty()) {
    if (options->layout != SyntheticLayout::kSequential) {
      throw InputError("--Synthetic.trajectory_path", "needs --Synthetic.layout sequential");
    }
    const GroundTruth trajectory = ReadGroundTruth(text.trajectory_path, GroundTruthFormat::kKitti);
    options->path = SyntheticPath::kGiven;
    for (const GroundTruthPose& pose : trajectory.poses) {
      options->given_poses.push_back(pose.cam_from_world);
    }
    if (!num_images_given) options->num_images = 0;
  }
  options->Check();
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
  if (const auto exit_code = ParseOptions(app, argc, argv)) return *exit_code;
  FinishSceneOptions(text, app.count("--Synthetic.num_images") > 0, &options);
  CheckFolderOutput("--output_path", output_path, {text.trajectory_path});
  CheckNewDatabasePath("--output_path", output_path + "/database.db", {text.trajectory_path});

  const SyntheticScene scene = BuildSyntheticScene(options);
  // Removed again if writing fails or is interrupted.
  CreatedOutput created(output_path);
  CreatedOutput created_database(output_path + "/database.db");
  WriteScene(scene, output_path, output_type == "TXT" ? ModelFormat::kText : ModelFormat::kBinary);
  created_database.Keep();
  created.Keep();
  PrintScene(scene, output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
