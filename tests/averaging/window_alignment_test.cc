#include "ramap/averaging/window_alignment.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// A drive around a loop: `num_images` centres on a rounded square, one unit apart along the path.
std::vector<Eigen::Vector3d> LoopDrive(int num_images) {
  std::vector<Eigen::Vector3d> centers;
  const double radius = num_images / (2 * M_PI);
  for (int i = 0; i < num_images; ++i) {
    const double a = 2 * M_PI * i / num_images;
    centers.emplace_back(radius * std::cos(a), 0.1 * std::sin(5 * a), radius * std::sin(a));
  }
  return centers;
}

// Windows of `length` images every `step`, each seen in its own frame: the true centres moved by
// the inverse of a random placement, plus `noise` per coordinate.
std::vector<std::map<uint32_t, Eigen::Vector3d>> LocalWindows(
    const std::vector<Eigen::Vector3d>& centers, int step, int length, double noise,
    std::mt19937* rng, std::vector<WindowPlacement>* truth) {
  std::uniform_real_distribution<double> scale(0.2, 5), offset(-50, 50);
  std::normal_distribution<double> jitter(0, noise);
  std::vector<std::map<uint32_t, Eigen::Vector3d>> windows;
  for (int begin = 0; begin + 1 < static_cast<int>(centers.size()); begin += step) {
    WindowPlacement placement;
    placement.scale = windows.empty() ? 1.0 : scale(*rng);
    placement.translation =
        windows.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(offset(*rng), offset(*rng), 0);
    std::map<uint32_t, Eigen::Vector3d> local;
    for (int i = begin; i < std::min<int>(begin + length, centers.size()); ++i) {
      const Eigen::Vector3d noisy =
          centers[i] + Eigen::Vector3d(jitter(*rng), jitter(*rng), jitter(*rng));
      local[i] = (noisy - placement.translation) / placement.scale;
    }
    windows.push_back(local);
    truth->push_back(placement);
  }
  return windows;
}

// The directions between the first and the last `count` images (the loop's closing pairs).
std::vector<PairDirection> ClosingDirections(const std::vector<Eigen::Vector3d>& centers,
                                             int count) {
  std::vector<PairDirection> directions;
  const int n = static_cast<int>(centers.size());
  for (int i = 0; i < count; ++i) {
    for (int j = n - count; j < n; ++j) {
      directions.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(j),
                            (centers[j] - centers[i]).normalized()});
    }
  }
  return directions;
}

// RMS of the placed centres (each image's mean over its windows) after the best similarity
// alignment to the truth: the drift that remains, not the gauge.
double AlignedRmsError(const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
                       const std::vector<WindowPlacement>& placements,
                       const std::vector<Eigen::Vector3d>& centers) {
  std::map<uint32_t, std::pair<Eigen::Vector3d, int>> sums;
  for (size_t w = 0; w < windows.size(); ++w) {
    for (const auto& [id, local] : windows[w]) {
      auto& [sum, count] = sums.try_emplace(id, Eigen::Vector3d::Zero(), 0).first->second;
      sum += placements[w].scale * local + placements[w].translation;
      ++count;
    }
  }
  Eigen::Matrix3Xd placed(3, sums.size()), truth(3, sums.size());
  int k = 0;
  for (const auto& [id, sum] : sums) {
    placed.col(k) = sum.first / sum.second;
    truth.col(k++) = centers[id];
  }
  const Eigen::Matrix4d sim = Eigen::umeyama(placed, truth, true);
  const Eigen::Matrix3Xd aligned =
      (sim.topLeftCorner<3, 3>() * placed).colwise() + sim.topRightCorner<3, 1>();
  return std::sqrt((aligned - truth).colwise().squaredNorm().mean());
}

TEST(WindowAlignment, ExactWindowsArePlacedExactly) {
  std::mt19937 rng(3);
  const std::vector<Eigen::Vector3d> centers = LoopDrive(300);
  std::vector<WindowPlacement> truth;
  const auto windows = LocalWindows(centers, 30, 40, 0.0, &rng, &truth);
  const std::vector<WindowPlacement> placements =
      AlignWindows(windows, ClosingDirections(centers, 5));
  ASSERT_EQ(placements.size(), truth.size());
  for (size_t w = 0; w < truth.size(); ++w) {
    EXPECT_NEAR(placements[w].scale, truth[w].scale, 1e-6 * truth[w].scale) << "window " << w;
    EXPECT_LT((placements[w].translation - truth[w].translation).norm(), 1e-5) << "window " << w;
  }
}

// Each window's own noise lets the scale drift along the chain of overlaps; the loop's closing
// directions bring the last windows back to the first. 0.02 units of noise on 1-unit steps.
TEST(WindowAlignment, LoopDirectionsBoundTheDriftOfNoisyWindows) {
  std::mt19937 rng(5);
  const std::vector<Eigen::Vector3d> centers = LoopDrive(600);
  std::vector<WindowPlacement> truth;
  const auto windows = LocalWindows(centers, 30, 40, 0.02, &rng, &truth);
  const double open = AlignedRmsError(windows, AlignWindows(windows, {}), centers);
  const double closed =
      AlignedRmsError(windows, AlignWindows(windows, ClosingDirections(centers, 10)), centers);
  EXPECT_LT(closed, 0.5 * open);
  EXPECT_LT(closed, 0.3);  // measured 0.175 (open: 1.13), on a loop 600 units long
}

TEST(WindowAlignment, AWindowSharingOneImageIsAnError) {
  std::mt19937 rng(7);
  const std::vector<Eigen::Vector3d> centers = LoopDrive(100);
  std::vector<WindowPlacement> truth;
  // Windows of 31 images every 30 share one image: their relative scale is free.
  const auto windows = LocalWindows(centers, 30, 31, 0.0, &rng, &truth);
  EXPECT_THROW(AlignWindows(windows, {}), StageFailure);
}

}  // namespace
}  // namespace ramap
