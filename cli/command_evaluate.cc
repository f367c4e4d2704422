// `ramap evaluate --model_path MODEL --ground_truth PATH --ground_truth_format FORMAT`: accuracy of
// a COLMAP model's camera poses against ground truth (eval/pose_metrics.h), as a table on stdout
// and optionally as JSON. Which images count as the input: pipeline/model_evaluation.h.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "options.h"
#include "ramap/pipeline/model_evaluation.h"
#include "ramap/util/number_list.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

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
  options.auc_thresholds_deg = ParseNumberList(auc_thresholds, "--auc_thresholds");
  options.Check();
  if (!output_path.empty()) {
    CheckFileOutput("--output_path", output_path,
                    {model_path, ground_truth_path, image_list_path, database_path});
  }

  ModelEvaluationInput input{model_path, ground_truth_path,
                             GroundTruthFormatFromName(ground_truth_format), image_list_path,
                             database_path};
  const PoseEvaluation evaluation = EvaluateModel(input, options);
  std::cout << FormatPoseEvaluation(evaluation);
  if (!output_path.empty()) {
    WritePoseEvaluationJson(evaluation, output_path);
    std::cout << "Wrote " << output_path << "\n";
  }
  return 0;
}

}  // namespace ramap::cli
