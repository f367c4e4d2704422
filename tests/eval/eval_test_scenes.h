// Small synthetic camera sets for the eval tests: seeded, no global random state.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "ramap/geometry/alignment.h"
#include "ramap/scene/rigid3.h"

namespace ramap::test {

inline Eigen::Quaterniond RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  // A normalised 4D Gaussian is uniform on the unit quaternions.
  return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

inline Eigen::Vector3d RandomVector(std::mt19937_64& rng, double sigma) {
  std::normal_distribution<double> normal(0.0, sigma);
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
}

inline Sim3d RandomSim3(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> log_scale(-2.0, 2.0);
  return Sim3d(std::exp(log_scale(rng)), RandomRotation(rng), RandomVector(rng, 10.0));
}

// Cameras with random orientations and centres spread over a few units; names "img_00", ...
inline std::map<std::string, Rigid3d> RandomCameras(int n, std::mt19937_64& rng) {
  std::map<std::string, Rigid3d> poses;
  for (int i = 0; i < n; ++i) {
    const Eigen::Quaterniond rotation = RandomRotation(rng);
    const Eigen::Vector3d centre = RandomVector(rng, 3.0);
    char name[16];
    std::snprintf(name, sizeof(name), "img_%02d", i);
    poses[name] = Rigid3d(rotation, -(rotation * centre));
  }
  return poses;
}

inline std::vector<std::string> Names(const std::map<std::string, Rigid3d>& poses) {
  std::vector<std::string> names;
  for (const auto& [name, pose] : poses) names.push_back(name);
  return names;
}

// The same cameras expressed in another world frame: new_from_old applied to every pose.
inline std::map<std::string, Rigid3d> Transformed(const std::map<std::string, Rigid3d>& poses,
                                                  const Sim3d& new_from_old) {
  std::map<std::string, Rigid3d> out;
  for (const auto& [name, pose] : poses) out[name] = TransformPose(new_from_old, pose);
  return out;
}

// A pose with the same centre and its orientation turned by `angle_deg` about `axis` (in the
// camera frame).
inline Rigid3d RotatedInPlace(const Rigid3d& pose, const Eigen::Vector3d& axis, double angle_deg) {
  const Eigen::Vector3d centre = CameraCenter(pose);
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized())) *
      pose.rotation;
  return Rigid3d(rotation, -(rotation * centre));
}

}  // namespace ramap::test
