// Cholesky factorisation of the normal equations of translation averaging, shifted by a small
// ridge when they are only semidefinite. Small systems are factorised densely: a translation
// window's ~150 camera columns couple nearly all with all, and CHOLMOD's supernodal path (its
// analysis, OpenMP and BLAS calls made for large fronts) takes far longer per factorisation of
// them than a dense LLT (BENCHMARKS.md, "Scale"). Large systems go to CHOLMOD, the pattern
// analysed once.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>

namespace ramap {

struct ShiftedCholeskyOptions {
  // Systems with at most this many columns are factorised densely (a dense LLT costs n^3 / 3
  // multiplications: 42 million at 500). Near the bound both ways take as long, as on the
  // one system of the 160-frame real sequence.
  int max_dense_columns = 500;
};

class ShiftedCholesky {
 public:
  // `pattern`: the matrices' sparsity pattern (lower triangle read; values ignored).
  explicit ShiftedCholesky(const Eigen::SparseMatrix<double>& pattern,
                           const ShiftedCholeskyOptions& options = ShiftedCholeskyOptions());

  // Factorises matrix + shift I (lower triangle read) with a shift of 1e-10, which keeps a weakly
  // constrained camera defined without moving the solution. When that fails (a camera
  // constrained only along a line, IRLS weights spanning many orders of magnitude: seen on
  // kitti07_first160 from ORB with a focal length guessed 2x too long, which lost its whole
  // model), the shift grows from 1e-10 of the largest diagonal entry until the factorisation
  // succeeds. Not relative from the start: exact pose priors weigh ~1e8 and a relative shift
  // would pull every camera by millimetres. Returns the shift; throws StageFailure when no shift
  // works or an entry is not finite.
  double Factorize(const Eigen::SparseMatrix<double>& matrix);

  // (matrix + shift I)^-1 rhs with the last factorisation.
  Eigen::VectorXd Solve(const Eigen::VectorXd& rhs) const;

  bool dense() const { return sparse_ == nullptr; }

 private:
  // One attempt with `shift`; whether it succeeded.
  bool TryFactorize(const Eigen::SparseMatrix<double>& matrix, double shift);

  Eigen::LLT<Eigen::MatrixXd> dense_;
  Eigen::MatrixXd dense_matrix_;
  std::unique_ptr<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>> sparse_;
};

}  // namespace ramap
