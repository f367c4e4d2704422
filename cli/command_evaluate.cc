// `ramap evaluate --model_path MODEL --ground_truth PATH --ground_truth_format FORMAT`: accuracy of
// a COLMAP model's camera poses against ground truth (eval/pose_metrics.h), as a table on stdout
// and optionally as JSON.
//
// Which images count as the input (unregistered ones are failures):
//   --image_list FILE   the names in FILE, one per line; else
//   --database_path DB  every image of the COLMAP database the model was made from; else
//   the ground truth's image names together with the model's (a model image without ground truth
//   is counted but cannot be scored). Ground truth matched by index (KITTI, TUM without names)
//   needs the first or second, unless the model registered exactly as many images as there are
//   poses: pose k belongs to the k-th input image in name order.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "options.h"
#include "ramap/eval/pose_metrics.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/image_list.h"
#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

std::vector<double> ParseThresholds(const std::string& text) {
  std::vector<double> thresholds;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      size_t used = 0;
      thresholds.push_back(std::stod(item, &used));
      if (item.find_first_not_of(" ", used) != std::string::npos) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw InputError("--auc_thresholds", "'" + item + "' is not a number");
    }
  }
  return thresholds;
}

// The input images (registered or not): the list, else the database's, else those the model and
// the ground truth name.
std::vector<std::string> InputImageNames(const std::string& image_list_path,
                                         const std::string& database_path,
                                         const std::map<std::string, Rigid3d>& estimated,
                                         const GroundTruth& ground_truth,
                                         const std::string& ground_truth_path) {
  std::vector<std::string> input_names;
  if (!image_list_path.empty()) {
    input_names = ReadImageList(image_list_path);
  } else if (!database_path.empty()) {
    input_names = ReadDatabaseImageNames(database_path);
  }

  if (input_names.empty()) {
    if (ground_truth.matched_by_index) {
      // Without a list, only a model that registered every image names them all.
      if (estimated.size() != ground_truth.poses.size()) {
        throw InputError(ground_truth_path,
                         "this ground truth matches poses to images by index (in name order), "
                         "and the model registered " +
                             std::to_string(estimated.size()) + " images for " +
                             std::to_string(ground_truth.poses.size()) +
                             " poses: give --image_list or --database_path");
      }
      for (const auto& [name, pose] : estimated) input_names.push_back(name);
    } else {
      std::set<std::string> names;
      for (const GroundTruthPose& pose : ground_truth.poses) names.insert(pose.image_name);
      for (const auto& [name, pose] : estimated) names.insert(name);
      input_names.assign(names.begin(), names.end());
    }
  }
  return input_names;
}

}  // namespace

int RunEvaluate(int argc, char** argv) {
  CLI::App app(
      "Scores a COLMAP model's camera poses against ground truth: registered images, ATE "
      "after Sim(3) alignment, rotation error, relative pose AUC.",
      "ramap evaluate");
  std::string model_path;
  std::string ground_truth_path;
  std::string ground_truth_format;
  std::string output_path;
  std::string image_list_path;
  std::string database_path;
  std::string auc_thresholds = "1,3,5,10";
  PoseEvaluationOptions options;
  bool robust = options.alignment.robust;
  app.add_option("--model_path", model_path, "COLMAP model folder (.bin or .txt)")->required();
  app.add_option("--ground_truth", ground_truth_path, "ground-truth file or folder")->required();
  app.add_option("--ground_truth_format", ground_truth_format,
                 "tum, kitti, strecha, middlebury or colmap")
      ->required();
  app.add_option("--output_path", output_path, "write the evaluation as JSON here");
  app.add_option("--image_list", image_list_path,
                 "the input images, one name per line (unregistered ones are failures)");
  app.add_option("--database_path", database_path,
                 "COLMAP database whose images are the input (when no --image_list)");
  app.add_option("--estimate_scale", options.alignment.estimate_scale,
                 "1: Sim(3) alignment; 0: SE(3), for metric reconstructions")
      ->capture_default_str();
  app.add_option("--robust_alignment", robust,
                 "RANSAC over triples of centres, then a refit on the inliers")
      ->capture_default_str();
  app.add_option("--robust_alignment_max_error", options.alignment.robust_max_error,
                 "inlier threshold of the robust alignment, in ground-truth units")
      ->check(AtLeast(0));
  app.add_option("--auc_thresholds", auc_thresholds, "relative pose AUC thresholds, degrees")
      ->capture_default_str();
  app.add_option("--min_baseline", options.min_baseline,
                 "pairs with a shorter ground-truth baseline score rotation only")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--ordered_pairs", options.ordered_pairs,
                 "score both orders of each pair, as COLMAP's benchmark")
      ->capture_default_str();
  if (const auto exit_code = ParseOptions(app, argc, argv)) return *exit_code;
  options.alignment.robust = robust;
  options.auc_thresholds_deg = ParseThresholds(auc_thresholds);
  options.Check();
  if (!output_path.empty()) {
    CheckFileOutput("--output_path", output_path,
                    {model_path, ground_truth_path, image_list_path, database_path});
  }

  const GroundTruthFormat format = GroundTruthFormatFromName(ground_truth_format);
  const Reconstruction model = ReadColmapModel(model_path);
  const std::map<std::string, Rigid3d> estimated = PosesByName(model, model_path);
  const GroundTruth ground_truth = ReadGroundTruth(ground_truth_path, format);

  const std::vector<std::string> input_names =
      InputImageNames(image_list_path, database_path, estimated, ground_truth, ground_truth_path);
  const std::map<std::string, Rigid3d> gt_poses = GroundTruthByImageName(ground_truth, input_names);

  const PoseEvaluation evaluation = EvaluatePoses(estimated, gt_poses, input_names, options);
  if (evaluation.num_with_ground_truth == 0) {
    const std::string inputs = !image_list_path.empty() ? "--image_list " + image_list_path
                               : !database_path.empty() ? "--database_path " + database_path
                                                        : "the model " + model_path;
    throw InputError(ground_truth_path, "none of the " + std::to_string(input_names.size()) +
                                            " images of " + inputs +
                                            " has a ground-truth pose here (another scene, or "
                                            "names that differ?)");
  }
  std::cout << FormatPoseEvaluation(evaluation);
  if (!output_path.empty()) {
    WritePoseEvaluationJson(evaluation, output_path);
    std::cout << "Wrote " << output_path << "\n";
  }
  return 0;
}

}  // namespace ramap::cli
