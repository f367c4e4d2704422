// Ground-truth poses keyed by image name, whichever way the ground-truth format identifies images.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ramap/io/trajectory.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

// Image name -> ground-truth cam_from_world. Named poses (Strecha, Middlebury, COLMAP, TUM with
// names) map by their names and `image_names` is not used. Index-matched poses (KITTI, TUM
// without names) map pose k to the k-th of `image_names` in name order, the convention of
// GroundTruth::matched_by_index. Throws InputError("ground truth", ...) on a name given twice or
// when index matching has fewer poses than names.
std::map<std::string, Rigid3d> GroundTruthPosesByName(const GroundTruth& ground_truth,
                                                      std::vector<std::string> image_names);

}  // namespace ramap
