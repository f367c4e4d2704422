// Scoring a COLMAP model's camera poses against ground truth (eval/pose_metrics.h), as `ramap
// evaluate` does.
//
// Which images count as the input (unregistered ones are failures):
//   image_list_path    the names in that file, one per line; else
//   database_path      every image of the COLMAP database the model was made from; else
//   the ground truth's image names together with the model's (a model image without ground truth
//   is counted but cannot be scored). Ground truth matched by index (KITTI, TUM without names)
//   needs the first or second, unless the model registered exactly as many images as there are
//   poses: pose k belongs to the k-th input image in name order.
#pragma once

#include <string>

#include "ramap/eval/pose_metrics.h"
#include "ramap/io/trajectory.h"

namespace ramap {

struct ModelEvaluationInput {
  std::string model_path;  // COLMAP model folder (.bin or .txt)
  std::string ground_truth_path;
  GroundTruthFormat ground_truth_format = GroundTruthFormat::kTum;
  std::string image_list_path;  // optional
  std::string database_path;    // optional
};

// Reads the model and the ground truth and scores the model's poses. Throws InputError when none
// of the input images has a ground-truth pose (another scene, or names that differ).
PoseEvaluation EvaluateModel(const ModelEvaluationInput& input,
                             const PoseEvaluationOptions& options);

}  // namespace ramap
