// Normal equations of a block-weighted linear least-squares problem, reassembled cheaply for new
// weights: sum_b w_b |B_b v|^2 over 3-row blocks B_b of a sparse matrix B, where some columns may
// be held at fixed values (moved to the right-hand side). The Gram matrix of every block is
// computed once and scattered into a sparsity pattern that never changes, so IRLS steps cost a
// weighted sum and a numeric refactorisation, not a sparse matrix product.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace ramap {

class BlockNormalEquations {
 public:
  // `B` has 3 rows per block. Columns listed in `holdable_columns` may later be held; each must
  // appear in one block only (as a per-pair scale does).
  BlockNormalEquations(const Eigen::SparseMatrix<double>& B,
                       const std::vector<int>& holdable_columns);

  // normal = sum_b w_b B_b^T B_b (lower triangle, the pattern fixed at construction) and
  // rhs = -sum_b w_b B_b^T B_b h, h holding `held_values` at the held columns (zero elsewhere);
  // a held column's row and column are replaced by the identity and its rhs by its value, so the
  // solution keeps it. `held` and `held_values` are indexed like `holdable_columns`.
  void Assemble(const Eigen::VectorXd& block_weights, const std::vector<bool>& held,
                const std::vector<double>& held_values, Eigen::SparseMatrix<double>* normal,
                Eigen::VectorXd* rhs) const;

  // The matrix with the pattern of the normal equations (zeros), for the symbolic analysis.
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }

 private:
  struct Block {
    std::vector<int> columns;      // increasing
    std::vector<double> gram;      // columns.size()^2, row-major
    std::vector<int> value_index;  // per gram entry with columns[r] >= columns[c]; -1 otherwise
    int holdable = -1;             // index into holdable_columns of its column, or -1
    int holdable_local = -1;       // position of that column in `columns`
  };
  std::vector<Block> blocks_;
  std::vector<int> holdable_columns_;
  std::vector<int> holdable_diagonal_index_;
  Eigen::SparseMatrix<double> pattern_;
};

}  // namespace ramap
