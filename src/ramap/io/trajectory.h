// Trajectories and ground truth: TUM (written and read), KITTI, Strecha .camera files, Middlebury
// *_par.txt, and a COLMAP model used as a reference.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ramap/io/colmap_model.h"
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
  // True for TUM: poses carry timestamps, which GroundTruthByImageName tries before the index.
  bool has_timestamps = false;
  std::vector<GroundTruthPose> poses;
  // The file or folder it was read from, for messages.
  std::string source = "ground truth";
};

// Reads ground truth at `path` (a file, or a folder for Strecha's gt_dense_cameras and COLMAP).
// Every pose is converted to cam_from_world (x_cam = R x_world + t). Rotation matrices must be
// orthonormal with det +1 to 1e-4 (then they are re-orthonormalised); values must be finite.
// Throws InputError naming the file and line (or the image) on any defect.
GroundTruth ReadGroundTruth(const std::string& path, GroundTruthFormat format);

// The ground-truth pose of each of `image_names` (every input image, registered or not), keyed by
// name; images without ground truth are absent. Matching:
//  - formats with names (Strecha, Middlebury, COLMAP): by name;
//  - TUM: by timestamp when the name of every image, minus its extension, is a number equal
//    (to 1e-6 s) to a timestamp of the file (e.g. "1305031098.6659.png", or what
//    WriteTumTrajectory wrote for numbered images); otherwise by index as below;
//  - by index (KITTI, TUM otherwise): pose i belongs to the i-th name in sorted order; the file
//    must have at least as many poses as there are images (InputError otherwise).
std::map<std::string, Rigid3d> GroundTruthByImageName(const GroundTruth& ground_truth,
                                                      std::vector<std::string> image_names);

// Writes the registered images of `reconstruction` in TUM format (timestamp tx ty tz qx qy qz qw,
// camera-to-world), in name order; the timestamp is the image name's number when it has one, else
// its index in name order. "Has one" means: every registered image's name minus its extension
// is a number (e.g. 000123.png -> 123); if any is not, all timestamps are indices, so that they
// stay distinct. Values are written with 17 significant digits (lossless). Staged write.
void WriteTumTrajectory(const Reconstruction& reconstruction, const std::string& path);

// WriteColmapModel for a command that changes a model's poses in place (bundle_adjuster,
// model_aligner): a trajectory_tum.txt that the mapper wrote beside the model is written again
// from the new poses, so that nothing in the folder describes the old ones.
void WriteColmapModelAndTrajectory(const Reconstruction& reconstruction, const std::string& path,
                                   ModelFormat format);

}  // namespace ramap
