#include "ramap/jobs/model_evaluation.h"

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/image_list.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

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

// A list that names no image of the model and none of the ground truth's is another scene's (or
// its names differ): said so, before ground truth matched by index is given to its names.
void CheckImageListNamesSome(const ModelEvaluationInput& input,
                             const std::vector<std::string>& listed,
                             const std::map<std::string, Rigid3d>& estimated,
                             const GroundTruth& ground_truth) {
  std::set<std::string> known;
  for (const auto& [name, pose] : estimated) known.insert(name);
  for (const GroundTruthPose& pose : ground_truth.poses) known.insert(pose.image_name);
  if (std::any_of(listed.begin(), listed.end(),
                  [&](const std::string& name) { return known.count(name) > 0; })) {
    return;
  }
  std::string examples;
  for (size_t k = 0; k < std::min<size_t>(listed.size(), 3); ++k)
    examples += (k ? ", " : "") + listed[k];
  throw InputError("--image_list", "none of the " + std::to_string(listed.size()) + " images of " +
                                       input.image_list_path + " (" + examples +
                                       (listed.size() > 3 ? ", ..." : "") +
                                       ") is in the model " + input.model_path +
                                       " or named by the ground truth " +
                                       input.ground_truth_path + " (another scene?)");
}

}  // namespace

PoseEvaluation EvaluateModel(const ModelEvaluationInput& input,
                             const PoseEvaluationOptions& options) {
  const Reconstruction model = ReadColmapModel(input.model_path);
  const std::map<std::string, Rigid3d> estimated = PosesByName(model, input.model_path);
  const GroundTruth ground_truth =
      ReadGroundTruth(input.ground_truth_path, input.ground_truth_format);
  const std::vector<std::string> input_names = InputImageNames(
      input.image_list_path, input.database_path, estimated, ground_truth, input.ground_truth_path);
  if (!input.image_list_path.empty()) CheckImageListNamesSome(input, input_names, estimated, ground_truth);
  const std::map<std::string, Rigid3d> gt_poses = GroundTruthByImageName(ground_truth, input_names);
  PoseEvaluation evaluation = EvaluatePoses(estimated, gt_poses, input_names, options);
  if (evaluation.num_with_ground_truth == 0) {
    const std::string inputs =
        !input.image_list_path.empty() ? "--image_list " + input.image_list_path
        : !input.database_path.empty() ? "--database_path " + input.database_path
                                       : "the model " + input.model_path;
    throw InputError(input.ground_truth_path,
                     "none of the " + std::to_string(input_names.size()) + " images of " + inputs +
                         " has a ground-truth pose here (another scene, or names that differ?)");
  }
  // Without a list the inputs are the model's names and the ground truth's together, so the
  // ground truth of another scene passes the check above with every one of its own names.
  if (evaluation.num_evaluated == 0 && !estimated.empty()) {
    throw InputError(input.ground_truth_path,
                     "none of the " + std::to_string(estimated.size()) + " images of the model " +
                         input.model_path +
                         " has a ground-truth pose here (another scene, or names that differ?)");
  }
  return evaluation;
}

}  // namespace ramap
