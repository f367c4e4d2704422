// Normal equations of a block-weighted linear least-squares problem, reassembled cheaply for new
// weights: sum_b w_b |B_b v|^2 over 3-row blocks B_b of a sparse matrix B, where some columns
// (each in one block only, as a per-pair scale is) are eliminated: a held one at a fixed value
// (moved to the right-hand side), a free one at its block's minimiser (the block's Schur
// complement). The equations are over the other columns only, so a problem of a few thousand
// cameras and tens of thousands of pair scales factorises as a camera system (the scales'
// single-column supernodes made each CHOLMOD factorisation much slower; BENCHMARKS.md, "Scale").
// The sparsity pattern, and where each block's entries go in it, are fixed once, so IRLS steps
// cost a weighted sum of the blocks' small Gram matrices and a numeric refactorisation, not a
// sparse matrix product.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace ramap {

class BlockNormalEquations {
 public:
  // `B` has 3 rows per block. Each column of `eliminated_columns` must appear in one block only.
  // The other columns are the reduced system's, in their order. `B` by rows, as its blocks are
  // read (a column-major B converts on the way in).
  BlockNormalEquations(const Eigen::SparseMatrix<double, Eigen::RowMajor>& B,
                       const std::vector<int>& eliminated_columns);

  // The reduced normal equations: normal (lower triangle, the pattern fixed at construction) and
  // rhs, whose solution u minimises sum_b w_b |B_b v|^2 over the kept columns of v, with every
  // held eliminated column at its value and every free one at its block's minimiser. `held` and
  // `held_values` are indexed like `eliminated_columns`. The blocks are summed on up to
  // `num_threads` threads, each over a fixed share of them, so the sums do not depend on timing.
  void Assemble(const Eigen::VectorXd& block_weights, const std::vector<bool>& held,
                const std::vector<double>& held_values, Eigen::SparseMatrix<double>* normal,
                Eigen::VectorXd* rhs, int num_threads = 1) const;

  // The full vector v from the reduced solution u: kept columns from u, held eliminated columns
  // at their values, free ones at their block's minimiser given u.
  Eigen::VectorXd Expand(const Eigen::VectorXd& reduced, const std::vector<bool>& held,
                         const std::vector<double>& held_values) const;

  // The matrix with the pattern of the reduced normal equations (zeros), for the symbolic analysis.
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }

 private:
  // The pattern of the reduced normal equations (lower triangle) and value_index_.
  void BuildPattern(int num_columns);

  // Adds blocks [begin, end) to the pattern's values and to rhs (Assemble).
  void AddBlocks(int begin, int end, const Eigen::VectorXd& block_weights,
                 const std::vector<bool>& held, const std::vector<double>& held_values,
                 double* values, double* rhs) const;

  // The Gram matrix of a block, sum_r B_rc B_rc' over its 3 rows, and its Schur complement are
  // computed at each assembly from the block's column vectors (3 entries each) rather than stored:
  // a track block of four cameras has 12 columns, whose 144 Gram entries and their pattern indices
  // were a large share of a long drive's memory (BENCHMARKS.md, "Scale"). Blocks are stored flat,
  // by offsets.
  std::vector<int> column_begin_;         // per block, its first entry in kept_ and vectors_
  std::vector<int> kept_;                 // reduced column indices, increasing within a block
  std::vector<Eigen::Vector3d> vectors_;  // each kept column's 3 entries in its block
  std::vector<int> value_begin_;          // per block, its first entry in value_index_
  std::vector<int> value_index_;          // lower triangle (i >= j), row by row: pattern entry
  std::vector<int> block_eliminated_;     // per block, index into eliminated_columns or -1
  std::vector<Eigen::Vector3d> eliminated_vectors_;  // per eliminated column, its 3 entries
  std::vector<int> eliminated_columns_;
  std::vector<int> eliminated_block_;  // per eliminated column, its block
  std::vector<int> kept_columns_;      // reduced index -> column of B
  int num_columns_ = 0;
  Eigen::SparseMatrix<double> pattern_;
};

}  // namespace ramap
