#include "ramap/eval/ground_truth_poses.h"

#include <gtest/gtest.h>

#include "ramap/util/error.h"

namespace ramap {
namespace {

GroundTruthPose Pose(const std::string& name, double x) {
  GroundTruthPose pose;
  pose.image_name = name;
  pose.cam_from_world.translation = Eigen::Vector3d(x, 0, 0);
  return pose;
}

TEST(EvalGroundTruthPoses, NamedPosesMapByName) {
  GroundTruth gt;
  gt.poses = {Pose("b.jpg", 2), Pose("a.jpg", 1)};
  const auto poses = GroundTruthPosesByName(gt, {"ignored.jpg"});
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses.at("a.jpg").translation.x(), 1);
  EXPECT_EQ(poses.at("b.jpg").translation.x(), 2);
  gt.poses.push_back(Pose("a.jpg", 3));
  EXPECT_THROW(GroundTruthPosesByName(gt, {}), InputError);
}

TEST(EvalGroundTruthPoses, IndexMatchedPosesFollowNameOrder) {
  GroundTruth gt;
  gt.matched_by_index = true;
  gt.poses = {Pose("", 0), Pose("", 1), Pose("", 2), Pose("", 3)};
  // Three images: the first three poses, in name order whatever the order given.
  const auto poses = GroundTruthPosesByName(gt, {"000002.png", "000000.png", "000001.png"});
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses.at("000000.png").translation.x(), 0);
  EXPECT_EQ(poses.at("000002.png").translation.x(), 2);
  EXPECT_THROW(GroundTruthPosesByName(gt, {"a", "b", "c", "d", "e"}), InputError);
  EXPECT_THROW(GroundTruthPosesByName(gt, {"a", "a"}), InputError);
}

}  // namespace
}  // namespace ramap
