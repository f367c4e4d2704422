// Synthetic scenes for the translation-averaging tests: cameras with known rotations and centres,
// the tracks of the points they see and the exact directions of the pairs that share enough.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "ramap/averaging/translation_averaging.h"

namespace ramap::translation_test {

struct Scene {
  std::map<uint32_t, Eigen::Quaterniond> rotations;  // cam_from_world
  std::map<uint32_t, Eigen::Vector3d> centers;
  std::vector<Eigen::Vector3d> points;
};

// Cameras along a straight line looking forward (+z): the degenerate case for pairwise directions.
inline Scene ForwardLine(int num_cameras, int num_points, std::mt19937& rng) {
  Scene scene;
  std::uniform_real_distribution<double> lateral(-8, 8), depth(0, 40);
  for (int i = 0; i < num_cameras; ++i) {
    scene.rotations[i + 1] = Eigen::Quaterniond::Identity();
    scene.centers[i + 1] = Eigen::Vector3d(0, 0, 1.0 * i);
  }
  for (int p = 0; p < num_points; ++p) {
    scene.points.emplace_back(lateral(rng), lateral(rng) * 0.4, 5 + depth(rng));
  }
  return scene;
}

// Cameras on a circle looking at its centre (an unordered-collection-like ring).
inline Scene Ring(int num_cameras, int num_points, std::mt19937& rng) {
  Scene scene;
  std::normal_distribution<double> cloud(0, 1.0);
  for (int i = 0; i < num_cameras; ++i) {
    const double a = 2 * M_PI * i / num_cameras;
    const Eigen::Vector3d c(6 * std::cos(a), 0.5 * std::sin(3 * a), 6 * std::sin(a));
    const Eigen::Vector3d forward = (-c).normalized();
    const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(forward).normalized();
    Eigen::Matrix3d world_from_cam;
    world_from_cam << right, forward.cross(right), forward;
    scene.rotations[i + 1] = Eigen::Quaterniond(world_from_cam.transpose());
    scene.centers[i + 1] = c;
  }
  for (int p = 0; p < num_points; ++p)
    scene.points.emplace_back(cloud(rng), cloud(rng), cloud(rng));
  return scene;
}

inline bool Sees(const Scene& scene, uint32_t id, const Eigen::Vector3d& X) {
  const Eigen::Vector3d x = scene.rotations.at(id) * (X - scene.centers.at(id));
  return x.z() > 0.5 && std::abs(x.x() / x.z()) < 0.8 && std::abs(x.y() / x.z()) < 0.6;
}

// Feature tracks and the bearings of their keypoints.
struct ObservedTracks {
  std::vector<Track> tracks;
  KeypointBearings bearings;
};

// Tracks of every point in every camera that sees it (a keypoint of its own in each), bearings
// rotated by `noise_rad`; pairs of cameras sharing >= 15 points get an exact direction.
inline void Observe(const Scene& scene, double noise_rad, std::mt19937& rng, ObservedTracks* tracks,
                    std::vector<PairDirection>* directions) {
  std::normal_distribution<double> noise(0, noise_rad);
  std::map<std::pair<uint32_t, uint32_t>, int> shared;
  for (const Eigen::Vector3d& X : scene.points) {
    Track track;
    std::vector<Eigen::Vector3d> rays;
    for (const auto& [id, rotation] : scene.rotations) {
      if (!Sees(scene, id, X)) continue;
      Eigen::Vector3d f = (rotation * (X - scene.centers.at(id))).normalized();
      rays.push_back(Eigen::AngleAxisd(noise(rng), f.unitOrthogonal()) * f);
      track.push_back({id, 0});
    }
    for (size_t a = 0; a < track.size(); ++a) {
      for (size_t b = a + 1; b < track.size(); ++b)
        ++shared[{track[a].image_id, track[b].image_id}];
    }
    if (track.size() < 2) continue;
    for (size_t k = 0; k < track.size(); ++k) {
      std::vector<Eigen::Vector3d>& keypoints = tracks->bearings[track[k].image_id];
      track[k].point2D_idx = static_cast<uint32_t>(keypoints.size());
      keypoints.push_back(rays[k]);
    }
    tracks->tracks.push_back(track);
  }
  for (const auto& [pair, count] : shared) {
    if (count < 15) continue;
    directions->push_back(
        {pair.first, pair.second,
         (scene.centers.at(pair.second) - scene.centers.at(pair.first)).normalized()});
  }
}

// Largest camera-centre error after the best similarity alignment, relative to the scene's extent.
inline double RelativeCenterError(const Scene& scene, const TranslationAveragingResult& result) {
  Eigen::Matrix3Xd estimated(3, result.centers.size()), truth(3, result.centers.size());
  int k = 0;
  for (const auto& [id, c] : result.centers) {
    estimated.col(k) = c;
    truth.col(k++) = scene.centers.at(id);
  }
  const Eigen::Matrix4d sim = Eigen::umeyama(estimated, truth, true);
  const Eigen::Matrix3Xd aligned =
      (sim.topLeftCorner<3, 3>() * estimated).colwise() + sim.topRightCorner<3, 1>();
  const double extent = (truth.colwise() - truth.rowwise().mean()).colwise().norm().maxCoeff();
  return (aligned - truth).colwise().norm().maxCoeff() / extent;
}

// A scene with the tracks and pair directions observed with `noise` radians.
struct ObservedScene {
  Scene scene;
  ObservedTracks tracks;
  std::vector<PairDirection> directions;
};

inline ObservedScene ObserveScene(Scene scene, double noise, std::mt19937* rng) {
  ObservedScene observed;
  observed.scene = std::move(scene);
  Observe(observed.scene, noise, *rng, &observed.tracks, &observed.directions);
  return observed;
}

// A ring of 30 cameras observed with 0.1 deg of noise.
inline ObservedScene NoisyRing(std::mt19937* rng) {
  Scene ring = Ring(30, 600, *rng);
  return ObserveScene(std::move(ring), 0.1 * M_PI / 180, rng);
}
}  // namespace ramap::translation_test
