// Normal equations of a block-weighted linear least-squares problem, reassembled cheaply for new
// weights: sum_b w_b |B_b v|^2 over 3-row blocks B_b of a sparse matrix B, where some columns
// (each in one block only, as a per-pair scale is) are eliminated: a held one at a fixed value
// (moved to the right-hand side), a free one at its block's minimiser (the block's Schur
// complement). The equations are over the other columns only, so a problem of a few thousand
// cameras and tens of thousands of pair scales factorises as a camera system (measured on a
// 1101-frame drive: the scales' single-column supernodes had made each CHOLMOD factorisation
// several times slower than the camera system's). The Gram matrix of every block (and its Schur
// complement) is computed once and scattered into a sparsity pattern that never changes, so IRLS
// steps cost a weighted sum and a numeric refactorisation, not a sparse matrix product.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace ramap {

class BlockNormalEquations {
 public:
  // `B` has 3 rows per block. Each column of `eliminated_columns` must appear in one block only.
  // The other columns are the reduced system's, in their order.
  BlockNormalEquations(const Eigen::SparseMatrix<double>& B,
                       const std::vector<int>& eliminated_columns);

  // The reduced normal equations: normal (lower triangle, the pattern fixed at construction) and
  // rhs, whose solution u minimises sum_b w_b |B_b v|^2 over the kept columns of v, with every
  // held eliminated column at its value and every free one at its block's minimiser. `held` and
  // `held_values` are indexed like `eliminated_columns`.
  void Assemble(const Eigen::VectorXd& block_weights, const std::vector<bool>& held,
                const std::vector<double>& held_values, Eigen::SparseMatrix<double>* normal,
                Eigen::VectorXd* rhs) const;

  // The full vector v from the reduced solution u: kept columns from u, held eliminated columns
  // at their values, free ones at their block's minimiser given u.
  Eigen::VectorXd Expand(const Eigen::VectorXd& reduced, const std::vector<bool>& held,
                         const std::vector<double>& held_values) const;

  // The matrix with the pattern of the reduced normal equations (zeros), for the symbolic analysis.
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }

 private:
  struct Block {
    std::vector<int> kept;         // reduced column indices of its kept columns, increasing
    std::vector<double> gram;      // kept x kept, row-major
    std::vector<double> schur;     // gram minus the eliminated column's coupling (free case)
    std::vector<double> coupling;  // gram entries between each kept column and the eliminated one
    double eliminated_gram = 0;    // the eliminated column's own Gram entry
    std::vector<int> value_index;  // per kept x kept entry in the lower triangle; -1 otherwise
    int eliminated = -1;           // index into eliminated_columns, or -1
  };
  std::vector<Block> blocks_;
  std::vector<int> eliminated_columns_;
  std::vector<int> eliminated_block_;  // per eliminated column, its block
  std::vector<int> kept_columns_;      // reduced index -> column of B
  int num_columns_ = 0;
  Eigen::SparseMatrix<double> pattern_;
};

}  // namespace ramap
