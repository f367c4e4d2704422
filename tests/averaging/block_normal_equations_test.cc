// BlockNormalEquations against a direct computation of B^T W B, with and without held columns.
#include "ramap/averaging/block_normal_equations.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace ramap {
namespace {

// 4 blocks of 3 rows over 5 columns; column 4 appears in the last block only (holdable).
Eigen::SparseMatrix<double> MakeMatrix() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(12, 5);
  const std::vector<std::vector<int>> block_columns = {{0, 1}, {1, 2, 3}, {0, 3}, {2, 4}};
  for (size_t b = 0; b < block_columns.size(); ++b) {
    for (int r = 0; r < 3; ++r) {
      for (const int c : block_columns[b]) dense(3 * b + r, c) = value(rng);
    }
  }
  return dense.sparseView();
}

TEST(BlockNormalEquations, MatchesTheDirectProduct) {
  const Eigen::SparseMatrix<double> B = MakeMatrix();
  const BlockNormalEquations equations(B, {4});
  const Eigen::Vector4d weights(0.5, 2.0, 1.0, 3.0);
  Eigen::SparseMatrix<double> normal;
  Eigen::VectorXd rhs;
  equations.Assemble(weights, {false}, {1.0}, &normal, &rhs);
  Eigen::VectorXd row_weights(12);
  for (int b = 0; b < 4; ++b) row_weights.segment<3>(3 * b).setConstant(weights(b));
  const Eigen::MatrixXd expected =
      Eigen::MatrixXd(B).transpose() * row_weights.asDiagonal() * Eigen::MatrixXd(B);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(normal).triangularView<Eigen::Lower>();
  EXPECT_LT((lower - Eigen::MatrixXd(expected.triangularView<Eigen::Lower>())).norm(), 1e-12);
  EXPECT_LT(rhs.norm(), 1e-15);
}

TEST(BlockNormalEquations, HeldColumnMovesToTheRightHandSide) {
  const Eigen::SparseMatrix<double> B = MakeMatrix();
  const BlockNormalEquations equations(B, {4});
  const Eigen::Vector4d weights(1.0, 1.0, 2.0, 0.5);
  Eigen::SparseMatrix<double> normal;
  Eigen::VectorXd rhs;
  equations.Assemble(weights, {true}, {2.5}, &normal, &rhs);
  // Direct: minimise sum_b w_b |B_b (v_free, 2.5)|^2 over the first four columns.
  Eigen::VectorXd row_weights(12);
  for (int b = 0; b < 4; ++b) row_weights.segment<3>(3 * b).setConstant(weights(b));
  const Eigen::MatrixXd dense(B);
  const Eigen::MatrixXd free = dense.leftCols(4);
  const Eigen::VectorXd offset = dense.col(4) * 2.5;
  const Eigen::VectorXd expected_free =
      (free.transpose() * row_weights.asDiagonal() * free)
          .ldlt()
          .solve(-free.transpose() * row_weights.asDiagonal() * offset);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(normal).triangularView<Eigen::Lower>();
  const Eigen::MatrixXd full =
      lower + lower.transpose() - Eigen::MatrixXd(lower.diagonal().asDiagonal());
  const Eigen::VectorXd solution = full.ldlt().solve(rhs);
  EXPECT_NEAR(solution(4), 2.5, 1e-12);
  EXPECT_LT((solution.head(4) - expected_free).norm(), 1e-10);
}

}  // namespace
}  // namespace ramap
