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

struct SynthesizeCommand {
  std::string output_path;
  ModelFormat output_format = ModelFormat::kBinary;
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
  std::string trajectory_path;
  SyntheticSceneOptions scene;
  bool descriptors = false;
  SyntheticDescriptorOptions descriptor;
};

const OptionTable<SynthesizeCommand>& SynthesizeCommandTable() {
  static const OptionTable<SynthesizeCommand> table = [] {
    OptionTable<SynthesizeCommand> t;
    t.push_back(Required(PathOption<SynthesizeCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "folder for database.db, ground_truth/ and ground_truth.txt (created)")));
    t.push_back(
        ModelFormatOption<SynthesizeCommand>([](auto& o) -> auto& { return o.output_format; }));
    t.push_back(
        DatabaseGenerationOption<SynthesizeCommand>([](auto& o) -> auto& { return o.generation; }));
    AppendOptions(
        SyntheticSceneOptionTable(), [](auto& o) -> auto& { return o.scene; }, &t);
    t.push_back(PathOption<SynthesizeCommand>(
        "Synthetic.trajectory_path", [](auto& o) -> auto& { return o.trajectory_path; },
        "KITTI odometry pose file whose poses the sequential cameras take (instead of "
        "--Synthetic.path); --Synthetic.num_images 0 takes all"));
    t.push_back(BoolOption<SynthesizeCommand>(
        "Synthetic.descriptors", [](auto& o) -> auto& { return o.descriptors; },
        "1: SIFT-like descriptors for every keypoint (one per 3D point, noisy per view), so that "
        "ramap matcher can match the database again"));
    AppendOptions(
        SyntheticDescriptorOptionTable(), [](auto& o) -> auto& { return o.descriptor; }, &t);
    return t;
  }();
  return table;
}

// A trajectory file replaces the generated path; without --Synthetic.num_images
// (`num_images_given`) all its poses are taken.
void TakeTrajectory(const std::string& path, bool num_images_given,
                    SyntheticSceneOptions* options) {
  if (path.empty()) return;
  if (options->layout != SyntheticLayout::kSequential) {
    throw InputError("--Synthetic.trajectory_path", "needs --Synthetic.layout sequential");
  }
  const GroundTruth trajectory = ReadGroundTruth(path, GroundTruthFormat::kKitti);
  options->path = SyntheticPath::kGiven;
  for (const GroundTruthPose& pose : trajectory.poses) {
    options->given_poses.push_back(pose.cam_from_world);
  }
  if (!num_images_given) options->num_images = 0;
}

}  // namespace

std::string SynthesizeOptionsMarkdown() {
  return OptionTableMarkdown(SynthesizeCommandTable(), SynthesizeCommand());
}

int RunSynthesize(int argc, char** argv) {
  CLI::App app(
      "Builds a synthetic scene with exact ground truth: a COLMAP database (keypoints, matches "
      "with outliers, verified two-view geometries), the true COLMAP model and a TUM trajectory.",
      "ramap synthesize");
  SynthesizeCommand command;
  if (const auto code = ParseCommandLine(app, SynthesizeCommandTable(), &command, argc, argv))
    return *code;
  SyntheticSceneOptions& options = command.scene;
  const std::string& output_path = command.output_path;
  TakeTrajectory(command.trajectory_path, app.count("--Synthetic.num_images") > 0, &options);
  options.Check();
  CheckFolderOutput("--output_path", output_path, {command.trajectory_path});
  CheckNewDatabasePath("--output_path", output_path + "/database.db", {command.trajectory_path});

  SyntheticScene scene = BuildSyntheticScene(options);
  if (command.descriptors) {
    command.descriptor.seed = options.seed;
    AddSyntheticDescriptors(command.descriptor, &scene);
  }
  // Removed again if writing fails or is interrupted.
  CreatedOutput created(output_path);
  CreatedOutput created_database(output_path + "/database.db");
  WriteScene(scene, output_path, command.output_format, command.generation);
  created_database.Keep();
  created.Keep();
  PrintScene(scene, output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
