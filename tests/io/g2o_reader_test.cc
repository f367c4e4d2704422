#include "ramap/io/g2o_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/synthetic/synthetic_rotation_graph.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

TEST(G2oReader, TinyGrid3DConventionMatchesVertices) {
  RAMAP_REQUIRE_SHARED_DATA(path, "sesync_posegraphs/tinyGrid3D.g2o");
  const G2oPoseGraph g2o = ReadG2oPoseGraph(path);
  EXPECT_EQ(g2o.graph.node_ids.size(), 9u);
  EXPECT_EQ(g2o.graph.edges.size(), 11u);
  EXPECT_FALSE(g2o.planar);
  // The first edge (0, 1) repeats vertex 1's pose relative to vertex 0 (the identity): in ramap's
  // convention R_01 = R_1 R_0^T.
  const RelativeRotationEdge& edge = g2o.graph.edges[0];
  ASSERT_EQ(edge.i, 0u);
  ASSERT_EQ(edge.j, 1u);
  const Eigen::Quaterniond R0 = g2o.vertex_rotations.at(0);
  const Eigen::Quaterniond R1 = g2o.vertex_rotations.at(1);
  EXPECT_LT(edge.R_ij.angularDistance(R1 * R0.conjugate()), 1e-6);
  // Information 25 on each rotation axis: kappa = 3 / (2 * 3 / 25).
  EXPECT_NEAR(edge.weight, 12.5, 1e-9);
}

TEST(G2oReader, SmallGrid3DAveragesToSmallResiduals) {
  RAMAP_REQUIRE_SHARED_DATA(path, "sesync_posegraphs/smallGrid3D.g2o");
  const G2oPoseGraph g2o = ReadG2oPoseGraph(path);
  EXPECT_EQ(g2o.graph.node_ids.size(), 125u);
  EXPECT_EQ(g2o.graph.edges.size(), 297u);
  const RotationAveragingResult result = AverageRotations(g2o.graph, {});
  for (bool estimated : result.estimated) EXPECT_TRUE(estimated);
  // The file's rotation noise is large (information 25 per axis: sigma 0.2 rad = 11.5 deg). The
  // same graph read with the opposite convention (R_ij inverted) is inconsistent around every
  // cycle, and its averaged residuals are much larger.
  RotationGraph inverted = g2o.graph;
  for (RelativeRotationEdge& edge : inverted.edges) edge.R_ij = edge.R_ij.conjugate();
  const RotationAveragingResult wrong = AverageRotations(inverted, {});
  const double median = Median(result.edge_residuals_deg);
  std::vector<double> wrong_residuals;
  for (double r : wrong.edge_residuals_deg) {
    if (!std::isnan(r)) wrong_residuals.push_back(r);
  }
  EXPECT_LT(median, 20.0);
  EXPECT_LT(2.0 * median, Median(wrong_residuals)) << median;
  // The vertex guess in the file explains the edges about as well as the average does.
  std::vector<double> vertex_residuals;
  for (const RelativeRotationEdge& edge : g2o.graph.edges) {
    vertex_residuals.push_back(
        EdgeResidualDeg(edge, g2o.vertex_rotations.at(edge.i), g2o.vertex_rotations.at(edge.j)));
  }
  std::cout << "median residual: averaged " << median << " deg, inverted convention "
            << Median(wrong_residuals) << " deg, file vertices " << Median(vertex_residuals)
            << " deg\n";
  EXPECT_LT(median, Median(vertex_residuals) + 1.0);
}

TEST(G2oReader, PlanarEdgesAreRotationsAboutZ) {
  test::TempDir dir;
  const std::string path = dir / "planar.g2o";
  std::ofstream(path) << "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0.5\n"
                         "# a comment\nFIX 0\n"
                         " EDGE_SE2 0 1 1 0 0.5 10 0 0 10 0 40\n";
  const G2oPoseGraph g2o = ReadG2oPoseGraph(path);
  EXPECT_TRUE(g2o.planar);
  ASSERT_EQ(g2o.graph.edges.size(), 1u);
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(g2o.graph.edges[0].R_ij.angularDistance(expected), 1e-12);
  EXPECT_EQ(g2o.graph.edges[0].weight, 40.0);
  EXPECT_LT(g2o.vertex_rotations.at(1).angularDistance(expected), 1e-12);
}

TEST(G2oReader, BadLinesNameFileAndLine) {
  test::TempDir dir;
  const std::string path = dir / "bad.g2o";
  std::ofstream(path) << "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nEDGE_SE3:QUAT 0 1 1 2 3\n";
  try {
    ReadG2oPoseGraph(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.source(), path);
    EXPECT_NE(std::string(error.what()).find("line 2"), std::string::npos) << error.what();
  }
  EXPECT_THROW(ReadG2oPoseGraph(dir / "missing.g2o"), InputError);
}

}  // namespace
}  // namespace ramap
