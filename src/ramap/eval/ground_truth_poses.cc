#include "ramap/eval/ground_truth_poses.h"

#include <algorithm>

#include "ramap/util/error.h"

namespace ramap {

std::map<std::string, Rigid3d> GroundTruthPosesByName(const GroundTruth& ground_truth,
                                                      std::vector<std::string> image_names) {
  std::map<std::string, Rigid3d> poses;
  if (!ground_truth.matched_by_index) {
    for (const GroundTruthPose& pose : ground_truth.poses) {
      if (!poses.emplace(pose.image_name, pose.cam_from_world).second) {
        throw InputError("ground truth", "image '" + pose.image_name + "' has two poses");
      }
    }
    return poses;
  }
  std::sort(image_names.begin(), image_names.end());
  if (std::adjacent_find(image_names.begin(), image_names.end()) != image_names.end()) {
    throw InputError("image list", "an image name appears twice");
  }
  if (image_names.size() > ground_truth.poses.size()) {
    throw InputError("ground truth", "poses are matched to images by index, but there are " +
                                         std::to_string(ground_truth.poses.size()) + " poses for " +
                                         std::to_string(image_names.size()) + " images");
  }
  for (size_t k = 0; k < image_names.size(); ++k) {
    poses[image_names[k]] = ground_truth.poses[k].cam_from_world;
  }
  return poses;
}

}  // namespace ramap
