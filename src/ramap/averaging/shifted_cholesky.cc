#include "ramap/averaging/shifted_cholesky.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "ramap/util/error.h"

namespace ramap {
namespace {

constexpr double kFirstShift = 1e-10;

}  // namespace

ShiftedCholesky::ShiftedCholesky(const Eigen::SparseMatrix<double>& pattern,
                                 const ShiftedCholeskyOptions& options) {
  if (pattern.cols() <= options.max_dense_columns) return;
  sparse_ = std::make_unique<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>();
  // The retries of Factorize answer CHOLMOD's "not positive definite" warnings: not for the
  // user's eyes.
  sparse_->cholmod().print = 0;
  sparse_->analyzePattern(pattern);
}

bool ShiftedCholesky::TryFactorize(const Eigen::SparseMatrix<double>& matrix, double shift) {
  if (sparse_) {
    sparse_->setShift(shift);
    sparse_->factorize(matrix);
    return sparse_->info() == Eigen::Success;
  }
  // The lower triangle, as LLT reads it.
  dense_matrix_.setZero(matrix.rows(), matrix.cols());
  for (int c = 0; c < matrix.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it) {
      if (it.row() >= it.col()) dense_matrix_(it.row(), it.col()) = it.value();
    }
  }
  dense_matrix_.diagonal().array() += shift;
  dense_.compute(dense_matrix_);
  // LLT rejects a pivot only when it is <= 0: a NaN one passes, and would spread into the solution.
  return dense_.info() == Eigen::Success && dense_.matrixLLT().diagonal().allFinite();
}

double ShiftedCholesky::Factorize(const Eigen::SparseMatrix<double>& matrix) {
  // No shift makes a matrix with a NaN or an infinity factorisable.
  for (int c = 0; c < matrix.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it) {
      if (!std::isfinite(it.value()))
        throw StageFailure("translation averaging: non-finite normal equations");
    }
  }
  if (TryFactorize(matrix, kFirstShift)) return kFirstShift;
  const double scale = std::max(1.0, matrix.diagonal().cwiseAbs().maxCoeff());
  for (const double relative_shift : {1e-10, 1e-8, 1e-6, 1e-4}) {
    if (TryFactorize(matrix, relative_shift * scale)) return relative_shift * scale;
  }
  throw StageFailure("translation averaging: factorisation failed");
}

Eigen::VectorXd ShiftedCholesky::Solve(const Eigen::VectorXd& rhs) const {
  if (sparse_) return sparse_->solve(rhs);
  return dense_.solve(rhs);
}

}  // namespace ramap
