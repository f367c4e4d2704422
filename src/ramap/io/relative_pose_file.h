// Text files of relative poses (the output of `ramap relative_poses`, an input of
// `ramap rotation_averager`) and of absolute rotations (the output of `ramap rotation_averager`).
//
// Relative poses, one edge per line, '#' starts a comment:
//   NAME1 NAME2 qw qx qy qz tx ty tz num_inliers flags
// (qw..qz, tx..tz) is cam2_from_cam1 (R_ij = R_j R_i^T, unit t_ij; zero t for a pure rotation),
// flags the RelativePoseFlags bits. Rotations, one image per line:
//   NAME qw qx qy qz
// cam_from_world, as COLMAP's images.txt. Values are written with 17 significant digits.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace ramap {

struct RelativePoseRecord {
  std::string image_name1;
  std::string image_name2;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // cam2_from_cam1
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         // unit, or zero
  int num_inliers = 0;
  uint32_t flags = 0;
};

struct RotationRecord {
  std::string image_name;
  Eigen::Quaterniond cam_from_world = Eigen::Quaterniond::Identity();
};

// Staged writes (nothing is left behind on failure); throw InputError naming the path, also for
// an image name that is empty or holds a blank (fields are blank-separated).
void WriteRelativePoses(const std::vector<RelativePoseRecord>& records, const std::string& path);
void WriteRotations(const std::vector<RotationRecord>& records, const std::string& path);

// Throws InputError naming the file and line for a line that does not parse, a non-finite value, a
// quaternion far from unit norm (|1 - |q|| > 1e-3; then normalised), a self pair or a negative
// inlier count.
std::vector<RelativePoseRecord> ReadRelativePoses(const std::string& path);

}  // namespace ramap
