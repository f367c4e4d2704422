// ShiftedCholesky, dense and through CHOLMOD: the same solutions of a definite system, the first
// shift for a semidefinite one, a relative shift for an indefinite one, and a clear failure.
#include "ramap/averaging/shifted_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <limits>
#include <random>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// A banded symmetric positive definite matrix (full, both triangles) of n columns.
Eigen::SparseMatrix<double> BandedDefinite(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 4, n);
  for (int r = 0; r < n + 4; ++r) {
    for (int c = std::max(0, r - 4); c < std::min(n, r + 1); ++c) A(r, c) = value(rng);
  }
  return Eigen::MatrixXd(A.transpose() * A).sparseView();
}

ShiftedCholeskyOptions Dense(bool dense) {
  ShiftedCholeskyOptions options;
  options.max_dense_columns = dense ? 1000 : 0;
  return options;
}

class ShiftedCholeskyTest : public ::testing::TestWithParam<bool> {};

TEST_P(ShiftedCholeskyTest, SolvesADefiniteSystemWithTheFirstShift) {
  const Eigen::SparseMatrix<double> matrix = BandedDefinite(60);
  ShiftedCholesky cholesky(matrix, Dense(GetParam()));
  EXPECT_EQ(cholesky.dense(), GetParam());
  EXPECT_EQ(cholesky.Factorize(matrix), 1e-10);
  const Eigen::VectorXd truth = Eigen::VectorXd::LinSpaced(60, -1, 2);
  const Eigen::VectorXd rhs = matrix * truth;
  EXPECT_LT((cholesky.Solve(rhs) - truth).norm(), 1e-6);
  // Refactorised with new values of the same pattern.
  const Eigen::SparseMatrix<double> doubled = 2.0 * matrix;
  cholesky.Factorize(doubled);
  EXPECT_LT((cholesky.Solve(rhs) - 0.5 * truth).norm(), 1e-6);
  // The lower triangle alone, as translation averaging's reduced normal equations hold it.
  const Eigen::SparseMatrix<double> lower = matrix.triangularView<Eigen::Lower>();
  ShiftedCholesky from_lower(lower, Dense(GetParam()));
  from_lower.Factorize(lower);
  EXPECT_LT((from_lower.Solve(rhs) - truth).norm(), 1e-6);
}

// A NaN entry is a failed factorisation, not a NaN solution.
TEST_P(ShiftedCholeskyTest, ANaNEntryIsAFailure) {
  Eigen::SparseMatrix<double> matrix = BandedDefinite(10);
  matrix.coeffRef(4, 4) = std::numeric_limits<double>::quiet_NaN();
  ShiftedCholesky cholesky(matrix, Dense(GetParam()));
  EXPECT_THROW(cholesky.Factorize(matrix), StageFailure);
}

// The normal equations of a free camera's gauge: singular, made definite by the first shift.
TEST_P(ShiftedCholeskyTest, SemidefiniteSystemsFactoriseWithTheFirstShift) {
  Eigen::MatrixXd laplacian(3, 3);
  laplacian << 1, -1, 0, -1, 2, -1, 0, -1, 1;
  const Eigen::SparseMatrix<double> matrix = laplacian.sparseView();
  ShiftedCholesky cholesky(matrix, Dense(GetParam()));
  EXPECT_EQ(cholesky.Factorize(matrix), 1e-10);
  const Eigen::Vector3d rhs(1, 0, -1);  // in the range: the solution is defined up to the gauge
  const Eigen::VectorXd solution = cholesky.Solve(rhs);
  EXPECT_LT((laplacian * solution - rhs).norm(), 1e-6);
}

// Slightly indefinite (rounding in IRLS weights of many orders of magnitude): the shift grows with
// the largest diagonal entry until the factorisation succeeds; far from definite, it fails clearly.
TEST_P(ShiftedCholeskyTest, TheShiftGrowsUntilTheFactorisationSucceedsOrFails) {
  Eigen::MatrixXd indefinite = Eigen::MatrixXd::Identity(4, 4) * 1e4;
  indefinite(3, 3) = -1e-3;
  const Eigen::SparseMatrix<double> matrix = indefinite.sparseView();
  ShiftedCholesky cholesky(matrix, Dense(GetParam()));
  const double shift = cholesky.Factorize(matrix);
  EXPECT_GT(shift, 1e-3);
  EXPECT_LE(shift, 1e-6 * 1e4);
  indefinite(3, 3) = -1e4;
  const Eigen::SparseMatrix<double> far = indefinite.sparseView();
  EXPECT_THROW(cholesky.Factorize(far), StageFailure);
}

INSTANTIATE_TEST_SUITE_P(DenseOrSparse, ShiftedCholeskyTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "dense" : "cholmod";
                         });

}  // namespace
}  // namespace ramap
