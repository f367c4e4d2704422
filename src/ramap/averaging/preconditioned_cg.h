// Conjugate gradients for the reweighted least-squares steps of rotation and translation
// averaging, preconditioned by the Cholesky factor of an earlier step's system. Late IRLS steps
// reweight little, so the old factor is nearly the inverse of the new matrix and a few iterations
// (a triangular solve pair and a sparse product each) replace a refactorisation.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace ramap {

struct PreconditionedCgOptions {
  // Iterations at most; 0 turns the method off (SolveByPreconditionedCg returns false at once).
  int max_iterations = 40;
  // Converged when the residual's norm is at most this times the right-hand side's (Frobenius
  // norms over all columns).
  double tolerance = 1e-8;
  // After this many iterations, the mean rate of the residual so far forecasts whether the rest
  // reach the tolerance within max_iterations; when not, it gives up at once: a step whose
  // reweighting moved the equations far converges slowly from the first iterations on.
  int iterations_before_forecast = 3;
};

// Y = f(X) for an n x k matrix X.
using MatrixOperator = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

// Solves A X = B (A symmetric positive definite, applied by `apply`) column by column, with
// `precondition` applying an approximation of A^-1, started from *solution. Returns whether the
// tolerance was reached; *solution is the result then, and unchanged otherwise. `iterations`, when
// given, receives the iterations done either way.
bool SolveByPreconditionedCg(const MatrixOperator& apply, const MatrixOperator& precondition,
                             const Eigen::MatrixXd& rhs, const PreconditionedCgOptions& options,
                             Eigen::MatrixXd* solution, int* iterations = nullptr);

}  // namespace ramap
