// BlockNormalEquations against direct dense solutions, with the eliminated column free and held.
#include "ramap/averaging/block_normal_equations.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace ramap {
namespace {

// 4 blocks of 3 rows over 5 columns; column 4 appears in the last block only (eliminable).
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

Eigen::VectorXd RowWeights(const Eigen::Vector4d& weights) {
  Eigen::VectorXd row_weights(12);
  for (int b = 0; b < 4; ++b) row_weights.segment<3>(3 * b).setConstant(weights(b));
  return row_weights;
}

// The reduced solution of the assembled equations, expanded to all five columns.
Eigen::VectorXd SolveAssembled(const BlockNormalEquations& equations,
                               const Eigen::Vector4d& weights, bool held, double value) {
  Eigen::SparseMatrix<double> normal;
  Eigen::VectorXd rhs;
  equations.Assemble(weights, {held}, {value}, &normal, &rhs);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(normal).triangularView<Eigen::Lower>();
  EXPECT_EQ(lower.rows(), 4);  // column 4 eliminated
  const Eigen::MatrixXd full =
      lower + lower.transpose() - Eigen::MatrixXd(lower.diagonal().asDiagonal());
  return equations.Expand(full.ldlt().solve(rhs), {held}, {value});
}

TEST(BlockNormalEquations, FreeColumnIsEliminatedByTheSchurComplementOfTheDirectProduct) {
  const Eigen::SparseMatrix<double> B = MakeMatrix();
  const BlockNormalEquations equations(B, {4});
  const Eigen::Vector4d weights(0.5, 2.0, 1.0, 3.0);
  Eigen::SparseMatrix<double> normal;
  Eigen::VectorXd rhs;
  equations.Assemble(weights, {false}, {0.0}, &normal, &rhs);
  // N = B^T W B; eliminating column 4: N_kk - N_k4 N_4k / N_44 over columns 0-3.
  const Eigen::MatrixXd N =
      Eigen::MatrixXd(B).transpose() * RowWeights(weights).asDiagonal() * Eigen::MatrixXd(B);
  const Eigen::MatrixXd schur =
      N.topLeftCorner(4, 4) - N.col(4).head(4) * N.row(4).head(4) / N(4, 4);
  const Eigen::MatrixXd lower = Eigen::MatrixXd(normal).triangularView<Eigen::Lower>();
  ASSERT_EQ(lower.rows(), 4);
  EXPECT_LT((lower - Eigen::MatrixXd(schur.triangularView<Eigen::Lower>())).norm(), 1e-12);
  EXPECT_LT(rhs.norm(), 1e-15);
  // Expand puts column 4 at its minimiser given the others: -N_4k u / N_44.
  const Eigen::Vector4d kept(0.3, -1.0, 2.0, 0.7);
  const Eigen::VectorXd full = equations.Expand(kept, {false}, {0.0});
  EXPECT_NEAR(full(4), -N.row(4).head(4).dot(kept) / N(4, 4), 1e-12);
  EXPECT_EQ(full.head(4), Eigen::VectorXd(kept));
}

TEST(BlockNormalEquations, HeldColumnMovesToTheRightHandSide) {
  const Eigen::SparseMatrix<double> B = MakeMatrix();
  const BlockNormalEquations equations(B, {4});
  const Eigen::Vector4d weights(1.0, 1.0, 2.0, 0.5);
  const Eigen::VectorXd solution = SolveAssembled(equations, weights, true, 2.5);
  // Direct: minimise sum_b w_b |B_b (v_free, 2.5)|^2 over the first four columns.
  const Eigen::VectorXd row_weights = RowWeights(weights);
  const Eigen::MatrixXd dense(B);
  const Eigen::MatrixXd free = dense.leftCols(4);
  const Eigen::VectorXd offset = dense.col(4) * 2.5;
  const Eigen::VectorXd expected_free =
      (free.transpose() * row_weights.asDiagonal() * free)
          .ldlt()
          .solve(-free.transpose() * row_weights.asDiagonal() * offset);
  EXPECT_NEAR(solution(4), 2.5, 1e-12);
  EXPECT_LT((solution.head(4) - expected_free).norm(), 1e-10);
}

// Many blocks over shared columns, as the cameras of a long drive share tracks: the assembled
// equations hold every entry of B^T W B in its place and no other, and a column that no block
// touches keeps its diagonal entry.
TEST(BlockNormalEquations, ManyOverlappingBlocksAssembleTheDirectProduct) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<int> column(0, 39);  // column 40 is in no block
  const int num_blocks = 60;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * num_blocks, 41);
  Eigen::VectorXd weights(num_blocks);
  for (int b = 0; b < num_blocks; ++b) {
    weights(b) = 0.5 + std::abs(value(rng));
    for (int k = 0; k < 4; ++k) {
      const int c = column(rng);
      for (int r = 0; r < 3; ++r) dense(3 * b + r, c) = value(rng);
    }
  }
  const Eigen::SparseMatrix<double> B = dense.sparseView();
  const BlockNormalEquations equations(B, {});
  Eigen::SparseMatrix<double> normal;
  Eigen::VectorXd rhs;
  equations.Assemble(weights, {}, {}, &normal, &rhs);
  Eigen::VectorXd row_weights(3 * num_blocks);
  for (int b = 0; b < num_blocks; ++b) row_weights.segment<3>(3 * b).setConstant(weights(b));
  const Eigen::MatrixXd N = dense.transpose() * row_weights.asDiagonal() * dense;
  ASSERT_EQ(normal.rows(), 41);
  EXPECT_LT((Eigen::MatrixXd(normal) - Eigen::MatrixXd(N.triangularView<Eigen::Lower>())).norm(),
            1e-12);
  // The pattern: the lower triangle of the blocks' shared columns, and every diagonal entry.
  int expected_entries = 0;
  for (int i = 0; i < 41; ++i) {
    for (int j = 0; j <= i; ++j) {
      bool shared = i == j;
      for (int b = 0; b < num_blocks && !shared; ++b) {
        shared = dense.block(3 * b, i, 3, 1).any() && dense.block(3 * b, j, 3, 1).any();
      }
      expected_entries += shared;
    }
  }
  EXPECT_EQ(equations.pattern().nonZeros(), expected_entries);
}

TEST(BlockNormalEquations, AColumnInTwoBlocksCannotBeEliminated) {
  EXPECT_THROW(BlockNormalEquations(MakeMatrix(), {3}), std::invalid_argument);
}

// Enough blocks to be summed in shares on two threads: the same equations as on one, the
// eliminated columns (one per block, as pair scales are) free and held alike.
TEST(BlockNormalEquations, TwoThreadsAssembleWhatOneDoes) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<int> column(0, 59);
  const int num_blocks = 6000;
  const int num_eliminated = 300;  // column 60 + k in block 20 k alone, across every share
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd weights(num_blocks);
  for (int b = 0; b < num_blocks; ++b) {
    weights(b) = 0.5 + std::abs(value(rng));
    for (int k = 0; k < 4; ++k) {
      const int c = column(rng);
      for (int r = 0; r < 3; ++r) triplets.emplace_back(3 * b + r, c, value(rng));
    }
    if (b % 20 == 0) {
      for (int r = 0; r < 3; ++r) triplets.emplace_back(3 * b + r, 60 + b / 20, value(rng));
    }
  }
  Eigen::SparseMatrix<double> B(3 * num_blocks, 60 + num_eliminated);
  B.setFromTriplets(triplets.begin(), triplets.end());  // repeated entries add up
  std::vector<int> eliminated(num_eliminated);
  std::vector<bool> held(num_eliminated);
  std::vector<double> held_values(num_eliminated);
  for (int k = 0; k < num_eliminated; ++k) {
    eliminated[k] = 60 + k;
    held[k] = k % 2 == 0;
    held_values[k] = 1.0 + 0.01 * k;
  }
  const BlockNormalEquations equations(B, eliminated);
  Eigen::SparseMatrix<double> one, two;
  Eigen::VectorXd rhs_one, rhs_two;
  equations.Assemble(weights, held, held_values, &one, &rhs_one, 1);
  equations.Assemble(weights, held, held_values, &two, &rhs_two, 2);
  ASSERT_EQ(two.nonZeros(), one.nonZeros());
  const Eigen::MatrixXd difference = Eigen::MatrixXd(two) - Eigen::MatrixXd(one);
  EXPECT_LT(difference.norm(), 1e-9 * Eigen::MatrixXd(one).norm());
  ASSERT_GT(rhs_one.norm(), 0);
  EXPECT_LT((rhs_two - rhs_one).norm(), 1e-9 * rhs_one.norm());
}

}  // namespace
}  // namespace ramap
