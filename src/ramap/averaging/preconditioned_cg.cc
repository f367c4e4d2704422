#include "ramap/averaging/preconditioned_cg.h"

#include <cmath>

namespace ramap {

bool SolveByPreconditionedCg(const MatrixOperator& apply, const MatrixOperator& precondition,
                             const Eigen::MatrixXd& rhs, const PreconditionedCgOptions& options,
                             Eigen::MatrixXd* solution, int* iterations) {
  if (iterations != nullptr) *iterations = 0;
  if (options.max_iterations <= 0) return false;
  const Eigen::Index num_columns = rhs.cols();
  Eigen::MatrixXd u = *solution;
  Eigen::MatrixXd residual = rhs - apply(u);
  const double target = options.tolerance * rhs.norm();
  Eigen::MatrixXd preconditioned = precondition(residual);
  Eigen::MatrixXd direction = preconditioned;
  Eigen::VectorXd products(num_columns);
  for (Eigen::Index c = 0; c < num_columns; ++c) {
    products[c] = residual.col(c).dot(preconditioned.col(c));
  }
  const double initial = residual.norm();
  int iteration = 0;
  for (; iteration < options.max_iterations; ++iteration) {
    const double norm = residual.norm();
    if (norm <= target) break;
    if (iteration >= options.iterations_before_forecast) {
      const double rate = std::pow(norm / initial, 1.0 / iteration);
      if (!(rate < 1) ||
          iteration + std::log(target / norm) / std::log(rate) > options.max_iterations) {
        break;
      }
    }
    const Eigen::MatrixXd applied = apply(direction);
    for (Eigen::Index c = 0; c < num_columns; ++c) {
      // A column already solved exactly has nothing left to move.
      if (products[c] == 0) continue;
      const double step = products[c] / direction.col(c).dot(applied.col(c));
      u.col(c) += step * direction.col(c);
      residual.col(c) -= step * applied.col(c);
    }
    preconditioned = precondition(residual);
    for (Eigen::Index c = 0; c < num_columns; ++c) {
      if (products[c] == 0) continue;
      const double next_product = residual.col(c).dot(preconditioned.col(c));
      direction.col(c) = preconditioned.col(c) + (next_product / products[c]) * direction.col(c);
      products[c] = next_product;
    }
  }
  if (iterations != nullptr) *iterations = iteration;
  if (!(residual.norm() <= target) || !u.allFinite()) return false;
  *solution = std::move(u);
  return true;
}

}  // namespace ramap
