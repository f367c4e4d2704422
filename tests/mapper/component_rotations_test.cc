// Stage 3 on one component: the averaged rotations of a noise-free line, its figures in the
// summary and its line in the report, and a wrong edge pruned and named with its reason.
#include "ramap/mapper/component_rotations.h"

#include <gtest/gtest.h>

#include "ramap/estimators/bearings.h"
#include "ramap/estimators/relative_poses.h"
#include "ramap/mapper/components.h"
#include "ramap/scene/image_order.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// A pass's input for a noise-free 20-frame line, and the view graph of its accepted pairs.
class ComponentRotations : public ::testing::Test {
 protected:
  ComponentRotations()
      : scene_(BuildSyntheticScene(
            test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 20))),
        options_(test::AveragingOnly()),
        bearings_(ComputeBearings(scene_.database, "synthetic")),
        pairs_(EstimateRelativePoses(scene_.database, bearings_, options_.relative_pose, 1)),
        order_(ImageIdsInCaptureOrder(scene_.database)) {
    StageReport report;
    graph_ = RotationGraphOfAcceptedPairs(scene_.database, pairs_, &report);
  }

  PassInput Input() const {
    return PassInput{
        scene_.database, options_, scene_.database.cameras, bearings_, pairs_, order_, true,
        priors_};
  }

  ComponentState Averaged(const RotationGraph& graph) const {
    ComponentState state;
    state.graph = graph;
    return AverageComponentRotations(Input(), std::move(state));
  }

  // The largest angle between an estimated relative rotation R_i R_j^T and the true one.
  double MaxRelativeErrorDeg(const std::map<uint32_t, Eigen::Quaterniond>& rotations) const {
    double max_error = 0;
    for (const auto& [i, rotation_i] : rotations) {
      for (const auto& [j, rotation_j] : rotations) {
        const Eigen::Quaterniond truth =
            scene_.ground_truth.images.at(i).cam_from_world.rotation *
            scene_.ground_truth.images.at(j).cam_from_world.rotation.conjugate();
        max_error = std::max(
            max_error, (rotation_i * rotation_j.conjugate()).angularDistance(truth) * 180 / M_PI);
      }
    }
    return max_error;
  }

  SyntheticScene scene_;
  MapperOptions options_;
  ImageBearings bearings_;
  std::vector<ImagePair> pairs_;
  std::vector<uint32_t> order_;
  PosePriors priors_;
  RotationGraph graph_;
};

TEST_F(ComponentRotations, EveryImageGetsItsTrueRotationAndTheStageReportsIt) {
  const ComponentState state = Averaged(graph_);
  ASSERT_EQ(state.rotations.size(), 20u);
  // Relative poses from float32 keypoints without noise: the mapper's exact-recovery bound.
  EXPECT_LT(MaxRelativeErrorDeg(state.rotations), 1e-3);
  ASSERT_EQ(state.edge_status.size(), graph_.edges.size());
  for (const EdgeStatus status : state.edge_status) EXPECT_EQ(status, EdgeStatus::kKept);
  EXPECT_EQ(state.summary.num_rotation_edges, static_cast<int>(graph_.edges.size()));
  EXPECT_EQ(state.summary.num_pruned_edges, 0);
  EXPECT_TRUE(state.summary.rotation_certified);
  EXPECT_TRUE(state.report.dropped_edges.empty());
  EXPECT_TRUE(state.report.image_reasons.empty());
  ASSERT_EQ(state.report.timings.size(), 1u);
  EXPECT_EQ(state.report.timings[0].stage, stage::kRotationAveraging);
}

TEST_F(ComponentRotations, AWrongEdgeIsPrunedAndNamedWithItsResidual) {
  // The edge between frames 5 and 6 measured 30 degrees off.
  RotationGraph graph = graph_;
  size_t wrong = graph.edges.size();
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (graph.edges[e].i == 5 && graph.edges[e].j == 6) wrong = e;
  }
  ASSERT_LT(wrong, graph.edges.size());
  graph.edges[wrong].R_ij =
      Eigen::Quaterniond(Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitY())) *
      graph.edges[wrong].R_ij;

  const ComponentState state = Averaged(graph);
  EXPECT_EQ(state.rotations.size(), 20u);
  EXPECT_EQ(state.edge_status[wrong], EdgeStatus::kPrunedResidual);
  EXPECT_EQ(state.summary.num_pruned_edges, 1);
  ASSERT_EQ(state.report.dropped_edges.size(), 1u);
  EXPECT_EQ(state.report.dropped_edges[0].what,
            scene_.database.images.at(5).name + " " + scene_.database.images.at(6).name);
  EXPECT_EQ(state.report.dropped_edges[0].reason.rfind("rotation residual ", 0), 0u)
      << state.report.dropped_edges[0].reason;
  EXPECT_NE(state.report.dropped_edges[0].reason.find("> threshold"), std::string::npos);
  // The other edges still fix every rotation.
  EXPECT_LT(MaxRelativeErrorDeg(state.rotations), 1e-3);
}

}  // namespace
}  // namespace ramap
