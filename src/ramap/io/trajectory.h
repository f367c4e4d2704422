// Trajectories and ground truth: TUM (written and read), KITTI, Strecha .camera files, Middlebury
// *_par.txt, and a COLMAP model used as a reference.
#pragma once

#include <string>
#include <vector>

#include "ramap/scene/reconstruction.h"
#include "ramap/scene/rigid3.h"

namespace ramap {

enum class GroundTruthFormat { kTum, kKitti, kStrecha, kMiddlebury, kColmap };

// Parses "tum", "kitti", "strecha", "middlebury", "colmap"; throws InputError otherwise.
GroundTruthFormat GroundTruthFormatFromName(const std::string& name);

struct GroundTruthPose {
  std::string image_name;  // empty when the format has none (KITTI, TUM): matched by index
  double timestamp = 0.0;  // TUM only
  Rigid3d cam_from_world;
};

struct GroundTruth {
  // When true, pose i belongs to the i-th image in name order (KITTI; TUM without names).
  bool matched_by_index = false;
  std::vector<GroundTruthPose> poses;
};

// Reads ground truth at `path` (a file, or a folder for Strecha's gt_dense_cameras and COLMAP).
GroundTruth ReadGroundTruth(const std::string& path, GroundTruthFormat format);

// Writes the registered images of `reconstruction` in TUM format (timestamp tx ty tz qx qy qz qw,
// camera-to-world), in name order; the timestamp is the image name's number when it has one, else
// its index in name order.
void WriteTumTrajectory(const Reconstruction& reconstruction, const std::string& path);

}  // namespace ramap
