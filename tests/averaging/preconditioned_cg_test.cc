// SolveByPreconditionedCg: the direct solution from a perturbed system's factor, column by
// column; off with max_iterations 0; and giving up, the start left unchanged, when a poor
// preconditioner cannot reach the tolerance in time.
#include "ramap/averaging/preconditioned_cg.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

namespace ramap {
namespace {

// A random symmetric positive definite n x n matrix, well conditioned.
Eigen::MatrixXd RandomDefinite(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::MatrixXd A(n + 5, n);
  for (int r = 0; r < A.rows(); ++r) {
    for (int c = 0; c < n; ++c) A(r, c) = value(rng);
  }
  return A.transpose() * A + Eigen::MatrixXd::Identity(n, n);
}

struct System {
  Eigen::MatrixXd matrix;
  Eigen::MatrixXd rhs;
};

struct Operators {
  MatrixOperator apply;
  MatrixOperator precondition;
};

// `matrix` and a preconditioner factorised from `factored`, as the IRLS steps use them.
Operators Make(const Eigen::MatrixXd& matrix, const Eigen::MatrixXd& factored) {
  const Eigen::LLT<Eigen::MatrixXd> factor(factored);
  return {[matrix](const Eigen::MatrixXd& x) -> Eigen::MatrixXd { return matrix * x; },
          [factor](const Eigen::MatrixXd& r) -> Eigen::MatrixXd { return factor.solve(r); }};
}

System MakeSystem(int n, int columns, uint32_t seed) {
  System system{RandomDefinite(n, seed), Eigen::MatrixXd(n, columns)};
  std::mt19937 rng(seed + 1);
  std::normal_distribution<double> value;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < columns; ++c) system.rhs(r, c) = value(rng);
  }
  return system;
}

TEST(PreconditionedCg, ReachesTheDirectSolutionFromAPerturbedFactor) {
  const System system = MakeSystem(40, 3, 1);
  // A reweighting of a few percent: the old factor nearly inverts the new matrix.
  Eigen::MatrixXd old_matrix = system.matrix;
  old_matrix.diagonal() *= 1.05;
  const Operators ops = Make(system.matrix, old_matrix);
  Eigen::MatrixXd solution = Eigen::MatrixXd::Zero(40, 3);
  int iterations = -1;
  ASSERT_TRUE(
      SolveByPreconditionedCg(ops.apply, ops.precondition, system.rhs, {}, &solution, &iterations));
  const Eigen::MatrixXd direct = system.matrix.llt().solve(system.rhs);
  EXPECT_LT((solution - direct).norm(), 1e-6 * direct.norm());
  EXPECT_GT(iterations, 0);
  EXPECT_LE(iterations, 15);
}

TEST(PreconditionedCg, SolvesEachColumnOnItsOwn) {
  const System system = MakeSystem(30, 2, 2);
  Eigen::MatrixXd old_matrix = system.matrix;
  old_matrix.diagonal() *= 1.1;
  const Operators ops = Make(system.matrix, old_matrix);
  // The second column starts at its exact solution: it must stay there while the first moves.
  const Eigen::MatrixXd direct = system.matrix.llt().solve(system.rhs);
  Eigen::MatrixXd solution = Eigen::MatrixXd::Zero(30, 2);
  solution.col(1) = direct.col(1);
  ASSERT_TRUE(SolveByPreconditionedCg(ops.apply, ops.precondition, system.rhs, {}, &solution));
  EXPECT_LT((solution.col(0) - direct.col(0)).norm(), 1e-6 * direct.col(0).norm());
  EXPECT_LT((solution.col(1) - direct.col(1)).norm(), 1e-6 * direct.col(1).norm());
}

TEST(PreconditionedCg, ZeroIterationsTurnItOff) {
  const System system = MakeSystem(10, 1, 3);
  const Operators ops = Make(system.matrix, system.matrix);
  PreconditionedCgOptions off;
  off.max_iterations = 0;
  Eigen::MatrixXd solution = Eigen::MatrixXd::Constant(10, 1, 7.0);
  int iterations = -1;
  EXPECT_FALSE(SolveByPreconditionedCg(ops.apply, ops.precondition, system.rhs, off, &solution,
                                       &iterations));
  EXPECT_EQ(iterations, 0);
  EXPECT_EQ(solution, Eigen::MatrixXd::Constant(10, 1, 7.0));
}

TEST(PreconditionedCg, GivesUpEarlyAndLeavesTheStartWhenThePreconditionerIsPoor) {
  // A factor of an unrelated matrix preconditions badly: the forecast after the first
  // iterations says the tolerance is out of reach, and the start must be left as it was.
  const System system = MakeSystem(200, 1, 4);
  const Operators ops = Make(system.matrix, RandomDefinite(200, 99));
  PreconditionedCgOptions options;
  options.max_iterations = 10;
  Eigen::MatrixXd solution = Eigen::MatrixXd::Zero(200, 1);
  int iterations = -1;
  EXPECT_FALSE(SolveByPreconditionedCg(ops.apply, ops.precondition, system.rhs, options, &solution,
                                       &iterations));
  EXPECT_EQ(solution, Eigen::MatrixXd::Zero(200, 1));
  EXPECT_GE(iterations, options.iterations_before_forecast);
  EXPECT_LT(iterations, options.max_iterations);
}

}  // namespace
}  // namespace ramap
