#include "ramap/geometry/alignment.h"

#include <gtest/gtest.h>

#include <random>

#include "eval/eval_test_scenes.h"
#include "ramap/util/error.h"

namespace ramap::test {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, std::mt19937_64& rng) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.push_back(RandomVector(rng, 5.0));
  return points;
}

std::vector<Eigen::Vector3d> Apply(const Sim3d& sim, const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : points) out.push_back(sim * p);
  return out;
}

void ExpectSimNear(const Sim3d& a, const Sim3d& b, double tolerance) {
  EXPECT_NEAR(a.scale, b.scale, tolerance * b.scale);
  EXPECT_NEAR(a.rotation.angularDistance(b.rotation), 0.0, tolerance);
  EXPECT_NEAR((a.translation - b.translation).norm(), 0.0,
              tolerance * (1.0 + b.translation.norm()));
}

TEST(EvalAlignment, RecoversExactSimilarity) {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const Sim3d truth = RandomSim3(rng);
    const std::vector<Eigen::Vector3d> source = RandomPoints(3 + trial, rng);
    const AlignmentResult result = AlignPoints(source, Apply(truth, source));
    ASSERT_TRUE(result.ok()) << AlignmentStatusName(result.status);
    EXPECT_EQ(result.num_inliers, 3 + trial);
    ExpectSimNear(result.target_from_source, truth, 1e-9);
  }
}

TEST(EvalAlignment, RigidModeKeepsUnitScale) {
  std::mt19937_64 rng(2);
  const std::vector<Eigen::Vector3d> source = RandomPoints(8, rng);
  Sim3d rigid = RandomSim3(rng);
  rigid.scale = 1.0;
  AlignmentOptions options;
  options.estimate_scale = false;
  AlignmentResult result = AlignPoints(source, Apply(rigid, source), options);
  ASSERT_TRUE(result.ok());
  ExpectSimNear(result.target_from_source, rigid, 1e-9);

  // On scaled data the rigid fit must not absorb the scale; the similarity fit does.
  Sim3d scaled = rigid;
  scaled.scale = 3.0;
  result = AlignPoints(source, Apply(scaled, source), options);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.target_from_source.scale, 1.0);
  result = AlignPoints(source, Apply(scaled, source));
  EXPECT_NEAR(result.target_from_source.scale, 3.0, 1e-9);
}

TEST(EvalAlignment, ReportsDegenerateInput) {
  const Eigen::Vector3d p(1.0, 2.0, 3.0);
  const Eigen::Vector3d d(0.3, -0.2, 0.9);
  EXPECT_EQ(AlignPoints({p, p + d}, {p, p + d}).status, AlignmentStatus::kTooFewPoints);
  EXPECT_EQ(AlignPoints({p, p + d, p - d}, {p, p + d}).status, AlignmentStatus::kTooFewPoints);
  EXPECT_EQ(AlignPoints({p, p, p, p}, {p, p + d, p - d, p + 2 * d}).status,
            AlignmentStatus::kCoincidentPoints);
  EXPECT_EQ(AlignPoints({p, p + d, p - d, p + 2 * d}, {p, p, p, p}).status,
            AlignmentStatus::kCoincidentPoints);
  // Collinear, even far from the origin and with unequal spacing.
  const Eigen::Vector3d far(1e4, -2e4, 5e3);
  const std::vector<Eigen::Vector3d> line = {far, far + d, far + 2.5 * d, far - 7 * d};
  const std::vector<Eigen::Vector3d> spread = {p, p + d, p + Eigen::Vector3d::UnitX(), p - d};
  EXPECT_EQ(AlignPoints(line, spread).status, AlignmentStatus::kCollinearPoints);
  EXPECT_EQ(AlignPoints(spread, line).status, AlignmentStatus::kCollinearPoints);
  AlignmentOptions robust;
  robust.robust = true;
  robust.robust_max_error = 0.1;
  EXPECT_EQ(AlignPoints(line, line, robust).status, AlignmentStatus::kCollinearPoints);
  // Planar (three non-collinear points) is enough.
  EXPECT_TRUE(AlignPoints(spread, spread).ok());
  EXPECT_FALSE(AlignPoints(line, spread).ok());
  EXPECT_EQ(AlignPoints(line, spread).target_from_source.scale, 1.0);
}

TEST(EvalAlignment, RobustFitIgnoresGrossOutlier) {
  std::mt19937_64 rng(3);
  const Sim3d truth = RandomSim3(rng);
  const std::vector<Eigen::Vector3d> source = RandomPoints(12, rng);
  std::vector<Eigen::Vector3d> target = Apply(truth, source);
  target[5] += Eigen::Vector3d(50.0, -40.0, 30.0) * truth.scale;

  const AlignmentResult plain = AlignPoints(source, target);
  ASSERT_TRUE(plain.ok());
  // The least-squares fit is pulled by the outlier...
  EXPECT_GT((plain.target_from_source * source[0] - target[0]).norm(), 0.1 * truth.scale);

  AlignmentOptions options;
  options.robust = true;
  options.robust_max_error = 0.01 * truth.scale;
  const AlignmentResult robust = AlignPoints(source, target, options);
  ASSERT_TRUE(robust.ok()) << AlignmentStatusName(robust.status);
  // ...the robust one is not, and flags exactly the outlier.
  ExpectSimNear(robust.target_from_source, truth, 1e-9);
  EXPECT_EQ(robust.num_inliers, 11);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(robust.inliers[i], i != 5) << i;

  // With many points the triples are sampled rather than enumerated; the result is the same.
  const std::vector<Eigen::Vector3d> many = RandomPoints(60, rng);
  std::vector<Eigen::Vector3d> many_target = Apply(truth, many);
  for (int i = 0; i < 60; i += 6) many_target[i] += RandomVector(rng, 20.0 * truth.scale);
  options.robust_max_iterations = 300;
  const AlignmentResult sampled = AlignPoints(many, many_target, options);
  ASSERT_TRUE(sampled.ok());
  ExpectSimNear(sampled.target_from_source, truth, 1e-9);
  EXPECT_EQ(sampled.num_inliers, 50);
}

TEST(EvalAlignment, RobustModeNeedsThreshold) {
  AlignmentOptions options;
  options.robust = true;
  EXPECT_THROW(options.Check(), InputError);
  options.robust_max_error = 1.0;
  EXPECT_NO_THROW(options.Check());
}

TEST(EvalAlignment, TransformPoseMovesCentreAndScalesCameraFrame) {
  std::mt19937_64 rng(4);
  const Sim3d sim = RandomSim3(rng);
  const Rigid3d pose(RandomRotation(rng), RandomVector(rng, 2.0));
  const Rigid3d moved = TransformPose(sim, pose);
  EXPECT_NEAR((CameraCenter(moved) - sim * CameraCenter(pose)).norm(), 0.0, 1e-9);
  // A world point seen from the moved camera is the old camera-frame point scaled.
  const Eigen::Vector3d x = RandomVector(rng, 4.0);
  EXPECT_NEAR((moved * (sim * x) - sim.scale * (pose * x)).norm(), 0.0, 1e-9);
  // Inverse undoes it.
  const Rigid3d back = TransformPose(sim.Inverse(), moved);
  EXPECT_NEAR(back.rotation.angularDistance(pose.rotation), 0.0, 1e-12);
  EXPECT_NEAR((back.translation - pose.translation).norm(), 0.0, 1e-9);
  EXPECT_NEAR((sim.ToMatrix() * sim.Inverse().ToMatrix() - Eigen::Matrix4d::Identity()).norm(), 0.0,
              1e-12);
}

}  // namespace
}  // namespace ramap::test
