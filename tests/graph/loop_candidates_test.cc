// FindLoopCandidates on a hand-made drive whose revisits are placed by hand: each rule (distance in
// median baselines, view angle, frame gap, pairs already matched, candidates per image) decides
// exactly the pairs it should, closest first.
#include "ramap/graph/loop_candidates.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "ramap/scene/features.h"
#include "test_support.h"

namespace ramap {
namespace {

// `image_id` with centre `center`, looking along +z turned by `turn_deg` about x.
Image ImageAt(uint32_t image_id, const Eigen::Vector3d& center, double turn_deg = 0.0) {
  Image image;
  image.image_id = image_id;
  image.camera_id = 1;
  image.name = "frame_" + std::to_string(image_id) + ".png";
  const Eigen::Quaterniond world_from_cam(
      Eigen::AngleAxisd(turn_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  image.cam_from_world =
      Rigid3d(world_from_cam.conjugate(), -(world_from_cam.conjugate() * center));
  return image;
}

// Frames 0-24 (images 1-25) one unit apart along x, looking along +z (the median baseline is 1),
// then four revisits of image 1's place (frames 25-28, within 20 frames of each other, so never
// candidates among themselves):
//   26: 0.49 away, same direction      -> a candidate at 0.49 baselines
//   27: 0.51 away                      -> too far
//   28: 0.30 away, turned by 29 degrees -> a candidate at 0.30
//   29: 0.35 away, turned by 31 degrees -> turned too far
struct Drive {
  Reconstruction model;
  std::vector<uint32_t> order;
};

Drive Revisits() {
  Drive drive;
  drive.model.cameras[1] = test::VgaPinholeCamera();
  for (uint32_t id = 1; id <= 25; ++id) {
    drive.model.images[id] = ImageAt(id, Eigen::Vector3d(id - 1.0, 0, 0));
  }
  drive.model.images[26] = ImageAt(26, Eigen::Vector3d(0, 0.49, 0));
  drive.model.images[27] = ImageAt(27, Eigen::Vector3d(0, -0.51, 0));
  drive.model.images[28] = ImageAt(28, Eigen::Vector3d(0, 0, 0.3), 29.0);
  drive.model.images[29] = ImageAt(29, Eigen::Vector3d(0, 0, -0.35), 31.0);
  for (uint32_t id = 1; id <= 29; ++id) drive.order.push_back(id);
  return drive;
}

// Neighbouring frames are one baseline apart: only revisits closer than half of one count.
LoopCandidateOptions HalfABaseline() {
  LoopCandidateOptions options;
  options.max_distance_baselines = 0.5;
  return options;
}

std::vector<std::pair<uint32_t, uint32_t>> Pairs(const std::vector<LoopCandidate>& candidates) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const LoopCandidate& candidate : candidates) {
    pairs.emplace_back(candidate.image_id1, candidate.image_id2);
  }
  return pairs;
}

using PairList = std::vector<std::pair<uint32_t, uint32_t>>;

TEST(LoopCandidates, CloseInPlaceAndDirectionClosestFirst) {
  const Drive drive = Revisits();
  const std::vector<LoopCandidate> candidates =
      FindLoopCandidates(drive.model, drive.order, {}, HalfABaseline());
  ASSERT_EQ(Pairs(candidates), (PairList{{1, 28}, {1, 26}}));
  // Distances in median baselines (1 unit) and angles between the optical axes, up to rounding.
  EXPECT_NEAR(candidates[0].distance_baselines, 0.30, 1e-12);
  EXPECT_NEAR(candidates[0].view_angle_deg, 29.0, 1e-6);
  EXPECT_NEAR(candidates[1].distance_baselines, 0.49, 1e-12);
  EXPECT_NEAR(candidates[1].view_angle_deg, 0.0, 1e-6);
  // A wider view angle lets image 29 in, at its distance.
  LoopCandidateOptions wider = HalfABaseline();
  wider.max_view_angle_deg = 32.0;
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {}, wider)),
            (PairList{{1, 28}, {1, 29}, {1, 26}}));
}

TEST(LoopCandidates, PairsAlreadyMatchedAreSkipped) {
  const Drive drive = Revisits();
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {ImagePairToPairId(28, 1)},
                                     HalfABaseline())),
            (PairList{{1, 26}}));
}

TEST(LoopCandidates, EachImageKeepsItsClosestCandidatesOnly) {
  const Drive drive = Revisits();
  LoopCandidateOptions one = HalfABaseline();
  one.max_candidates_per_image = 1;
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {}, one)), (PairList{{1, 28}}));
}

TEST(LoopCandidates, FrameGapCountsEveryFrameOfTheCaptureOrder) {
  Drive drive = Revisits();
  // Image 26 is frame 25 and image 28 frame 27: a gap of 26 keeps image 28 alone.
  LoopCandidateOptions gap = HalfABaseline();
  gap.min_frame_gap = 26;
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {}, gap)), (PairList{{1, 28}}));
  gap.min_frame_gap = 27;
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {}, gap)), (PairList{{1, 28}}));
  // An image the model left out is still a frame of the capture order...
  drive.model.images.erase(10);
  EXPECT_EQ(Pairs(FindLoopCandidates(drive.model, drive.order, {}, gap)), (PairList{{1, 28}}));
  // ...while one the order does not hold is none: image 28 becomes frame 26.
  std::vector<uint32_t> without_10 = drive.order;
  without_10.erase(std::find(without_10.begin(), without_10.end(), 10u));
  EXPECT_TRUE(FindLoopCandidates(drive.model, without_10, {}, gap).empty());
}

TEST(LoopCandidates, ACameraThatNeverMovesRevisitsNothing) {
  Reconstruction still;
  std::vector<uint32_t> order;
  for (uint32_t id = 1; id <= 40; ++id) {
    still.images[id] = ImageAt(id, Eigen::Vector3d(1, 2, 3));
    order.push_back(id);
  }
  EXPECT_TRUE(FindLoopCandidates(still, order, {}, LoopCandidateOptions()).empty());
  EXPECT_TRUE(FindLoopCandidates(Reconstruction(), {}, {}, LoopCandidateOptions()).empty());
}

TEST(LoopCandidates, BadOptionsNameTheOption) {
  LoopCandidateOptions options;
  options.min_frame_gap = 1;
  const Drive drive = Revisits();
  test::ExpectInputError([&] { FindLoopCandidates(drive.model, drive.order, {}, options); },
                         {"--LoopClosure.min_frame_gap"});
}

}  // namespace
}  // namespace ramap
