#include "ramap/geometry/epipolar_refinement.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numeric>
#include <random>

namespace ramap {
namespace {

// Bearings of random points (depth 4-12 ahead of camera 1) in both cameras of x2 = R x1 + t, with
// `noise` radians of Gaussian perturbation on each bearing.
struct BearingPair {
  std::vector<Eigen::Vector3d> f1, f2;
  std::vector<int> all;
};

BearingPair MakeBearings(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, int count,
                         double noise, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> spread(-0.6, 0.6), depth(4, 12);
  std::normal_distribution<double> jitter(0, noise);
  BearingPair pair;
  while (static_cast<int>(pair.f1.size()) < count) {
    const Eigen::Vector3d x1 = depth(rng) * Eigen::Vector3d(spread(rng), spread(rng), 1);
    const Eigen::Vector3d x2 = R * x1 + t;
    if (x2.z() <= 0) continue;
    const Eigen::Vector3d n1(jitter(rng), jitter(rng), jitter(rng));
    const Eigen::Vector3d n2(jitter(rng), jitter(rng), jitter(rng));
    pair.f1.push_back((x1.normalized() + n1).normalized());
    pair.f2.push_back((x2.normalized() + n2).normalized());
  }
  pair.all.resize(pair.f1.size());
  std::iota(pair.all.begin(), pair.all.end(), 0);
  return pair;
}

double Cost(const BearingPair& pair, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  double cost = 0;
  for (size_t k = 0; k < pair.f1.size(); ++k) {
    cost += std::pow(t.dot((R * pair.f1[k]).cross(pair.f2[k])), 2);
  }
  return cost;
}

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

const Eigen::Matrix3d kTrueRotation =
    Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1, 0.1).normalized()).toRotationMatrix();
const Eigen::Vector3d kTrueTranslation = Eigen::Vector3d(1, 0.1, 0.2);

TEST(EpipolarRefinement, NoiseFreeBearingsReachTheTruePoseFromAFewDegreesAway) {
  const BearingPair pair = MakeBearings(kTrueRotation, kTrueTranslation, 100, 0.0, 1);
  Eigen::Matrix3d R =
      kTrueRotation * Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, -1, 2).normalized());
  Eigen::Vector3d t =
      (kTrueTranslation.normalized() + Eigen::Vector3d(0, 0.05, -0.05)).normalized();
  ASSERT_GT(AngleDeg(R, kTrueRotation), 2.5);
  ASSERT_TRUE(RefineEpipolarPose(pair.f1, pair.f2, pair.all, &R, &t));
  EXPECT_LT(AngleDeg(R, kTrueRotation), 1e-6);
  EXPECT_NEAR(t.dot(kTrueTranslation.normalized()), 1.0, 1e-12);
  EXPECT_NEAR(t.norm(), 1.0, 1e-12);
  EXPECT_NEAR((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST(EpipolarRefinement, NoisyBearingsEndAtAStationaryPointBelowTheTruePosesCost) {
  const BearingPair pair = MakeBearings(kTrueRotation, kTrueTranslation, 300, 1e-3, 2);
  Eigen::Matrix3d R = kTrueRotation * Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitZ());
  Eigen::Vector3d t = kTrueTranslation.normalized();
  ASSERT_TRUE(RefineEpipolarPose(pair.f1, pair.f2, pair.all, &R, &t));
  const double refined = Cost(pair, R, t);
  // The minimum is at or below the truth's cost and near the truth (1 mrad noise, 300 matches).
  EXPECT_LE(refined, Cost(pair, kTrueRotation, kTrueTranslation.normalized()));
  EXPECT_LT(AngleDeg(R, kTrueRotation), 0.1);
  // Stationary: no small perturbation of the rotation lowers the cost further.
  for (const Eigen::Vector3d& axis :
       {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()}) {
    for (const double angle : {-1e-4, 1e-4}) {
      const Eigen::Matrix3d nudged = R * Eigen::AngleAxisd(angle, axis);
      EXPECT_GE(Cost(pair, nudged, t), refined * (1 - 1e-9));
    }
  }
}

TEST(EpipolarRefinement, OnlyTheGivenMatchesCount) {
  BearingPair pair = MakeBearings(kTrueRotation, kTrueTranslation, 60, 0.0, 3);
  // Ten gross outliers outside `indices` do not pull the fit.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> gauss(0, 1);
  const std::vector<int> clean = pair.all;
  for (int k = 0; k < 10; ++k) {
    pair.f1.push_back(Eigen::Vector3d(gauss(rng), gauss(rng), 3).normalized());
    pair.f2.push_back(Eigen::Vector3d(gauss(rng), gauss(rng), 3).normalized());
  }
  Eigen::Matrix3d R = kTrueRotation * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY());
  Eigen::Vector3d t = kTrueTranslation.normalized();
  ASSERT_TRUE(RefineEpipolarPose(pair.f1, pair.f2, clean, &R, &t));
  EXPECT_LT(AngleDeg(R, kTrueRotation), 1e-6);
}

}  // namespace
}  // namespace ramap
