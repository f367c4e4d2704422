// Stage 3 of the mapper as rotation_averager uses it: the view graph of relative pose records
// and the averaging of a sequence through keyframe windows against an unordered collection.
#include "ramap/estimators/rotations.h"

#include <gtest/gtest.h>

#include "ramap/geometry/rotation.h"
#include "ramap/synthetic/synthetic_rotation_graph.h"

namespace ramap {
namespace {

TEST(RotationStage, RecordsBecomeAGraphNumberedByFirstAppearance) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  const std::vector<RelativePoseRecord> records = {
      {"b.png", "a.png", q, Eigen::Vector3d::UnitX(), 40, 0},
      {"a.png", "c.png", q, Eigen::Vector3d::UnitX(), 0, 0}};
  std::vector<std::string> names;
  const RotationGraph graph = RotationGraphOfRecords(records, &names);
  EXPECT_EQ(names, (std::vector<std::string>{"b.png", "a.png", "c.png"}));
  EXPECT_EQ(graph.node_ids, (std::vector<uint32_t>{0, 1, 2}));
  ASSERT_EQ(graph.edges.size(), 2u);
  EXPECT_EQ(graph.edges[0].i, 0u);
  EXPECT_EQ(graph.edges[0].j, 1u);
  EXPECT_EQ(graph.edges[0].weight, 40.0);
  EXPECT_EQ(graph.edges[1].weight, 1.0);  // a record without inliers still counts once
  EXPECT_EQ(RelativeRotationWeight(-3), 1.0);
}

TEST(RotationStage, EdgeWeightsFollowTheFocalLengthsOnAuto) {
  FeatureDatabase database;
  database.cameras[1].has_prior_focal_length = true;
  database.cameras[2].has_prior_focal_length = true;
  EXPECT_TRUE(UseRotationEdgeWeights(EdgeWeighting::kAuto, database));
  EXPECT_FALSE(UseRotationEdgeWeights(EdgeWeighting::kOff, database));
  database.cameras[2].has_prior_focal_length = false;  // a guessed focal length
  EXPECT_FALSE(UseRotationEdgeWeights(EdgeWeighting::kAuto, database));
  EXPECT_TRUE(UseRotationEdgeWeights(EdgeWeighting::kOn, database));
}

TEST(RotationStage, SequenceThroughKeyframesAndCollectionAtOnceAgree) {
  SyntheticRotationGraphOptions options;
  options.num_nodes = 120;
  options.noise_deg = 0.5;
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(options);
  std::vector<uint32_t> order = synthetic.graph.node_ids;
  const RotationStageResult sequence = AverageGraphRotations(
      synthetic.graph, order, true, KeyframeOptions(), RotationAveragingOptions());
  const RotationStageResult collection = AverageGraphRotations(
      synthetic.graph, order, false, KeyframeOptions(), RotationAveragingOptions());
  EXPECT_GT(sequence.num_keyframes, 1);
  EXPECT_EQ(collection.num_keyframes, 0);
  for (const RotationStageResult* result : {&sequence, &collection}) {
    const RotationAveragingResult& rotations = result->rotations;
    ASSERT_EQ(rotations.node_ids.size(), synthetic.graph.node_ids.size());
    // Against the truth, up to the gauge: the relative rotation of every node to node 0.
    for (size_t k = 1; k < rotations.node_ids.size(); ++k) {
      ASSERT_TRUE(rotations.estimated[k]);
      const Eigen::Quaterniond estimated =
          rotations.rotations[k] * rotations.rotations[0].conjugate();
      const Eigen::Quaterniond truth =
          synthetic.true_rotations[k] * synthetic.true_rotations[0].conjugate();
      EXPECT_LT(RotationAngleDeg(estimated, truth), 2.0) << k;
    }
  }
}

}  // namespace
}  // namespace ramap
