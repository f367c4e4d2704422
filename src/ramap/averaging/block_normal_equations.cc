#include "ramap/averaging/block_normal_equations.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace ramap {
namespace {

// Index of entry (row, col) in a compressed column-major matrix's value array.
int ValueIndex(const Eigen::SparseMatrix<double>& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  if (it == end || *it != row) throw std::logic_error("BlockNormalEquations: entry not in pattern");
  return static_cast<int>(it - m.innerIndexPtr());
}

// The columns of block b of a row-major B with their 3 entries, by increasing column.
std::map<int, Eigen::Vector3d> BlockColumns(const Eigen::SparseMatrix<double, Eigen::RowMajor>& B,
                                            int b) {
  std::map<int, Eigen::Vector3d> entries;
  for (int r = 0; r < 3; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B, 3 * b + r); it; ++it) {
      auto [slot, inserted] = entries.emplace(it.col(), Eigen::Vector3d::Zero());
      slot->second(r) = it.value();
    }
  }
  return entries;
}

}  // namespace

BlockNormalEquations::BlockNormalEquations(const Eigen::SparseMatrix<double>& B,
                                           const std::vector<int>& eliminated_columns)
    : eliminated_columns_(eliminated_columns),
      eliminated_block_(eliminated_columns.size(), -1),
      num_columns_(static_cast<int>(B.cols())) {
  if (B.rows() % 3 != 0)
    throw std::invalid_argument("BlockNormalEquations: rows not in blocks of 3");
  std::vector<int> eliminated_index(B.cols(), -1);
  for (size_t k = 0; k < eliminated_columns.size(); ++k) {
    eliminated_index.at(eliminated_columns[k]) = static_cast<int>(k);
  }
  std::vector<int> reduced_index(B.cols(), -1);
  for (int c = 0; c < B.cols(); ++c) {
    if (eliminated_index[c] >= 0) continue;
    reduced_index[c] = static_cast<int>(kept_columns_.size());
    kept_columns_.push_back(c);
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = B;
  std::vector<Eigen::Triplet<double>> triplets;
  blocks_.resize(B.rows() / 3);
  for (size_t b = 0; b < blocks_.size(); ++b) {
    Block& block = blocks_[b];
    std::vector<Eigen::Vector3d> kept_vectors;
    Eigen::Vector3d eliminated_vector = Eigen::Vector3d::Zero();
    for (const auto& [column, vector] : BlockColumns(rows, static_cast<int>(b))) {
      if (eliminated_index[column] >= 0) {
        if (eliminated_block_[eliminated_index[column]] >= 0) {
          throw std::invalid_argument("BlockNormalEquations: an eliminated column in two blocks");
        }
        block.eliminated = eliminated_index[column];
        eliminated_block_[block.eliminated] = static_cast<int>(b);
        eliminated_vector = vector;
        continue;
      }
      block.kept.push_back(reduced_index[column]);
      kept_vectors.push_back(vector);
    }
    const size_t n = block.kept.size();
    block.gram.resize(n * n);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        block.gram[i * n + j] = kept_vectors[i].dot(kept_vectors[j]);
        if (block.kept[i] >= block.kept[j])
          triplets.emplace_back(block.kept[i], block.kept[j], 0.0);
      }
    }
    // Only blocks with an eliminated column keep its coupling and their Schur complement (most
    // blocks, the tracks', have none: copying their Gram matrices cost 36 of the 613 MiB peak on
    // the KITTI 06 drive of scripts/bench_scale.sh).
    if (block.eliminated < 0) continue;
    block.eliminated_gram = eliminated_vector.squaredNorm();
    block.coupling.resize(n);
    for (size_t i = 0; i < n; ++i) block.coupling[i] = kept_vectors[i].dot(eliminated_vector);
    block.schur = block.gram;
    if (block.eliminated_gram > 0) {
      for (size_t i = 0; i < n; ++i) {
        for (size_t j = 0; j < n; ++j) {
          block.schur[i * n + j] -= block.coupling[i] * block.coupling[j] / block.eliminated_gram;
        }
      }
    }
  }
  // Every diagonal entry, so that the pattern is complete even for columns no block touches.
  const int num_kept = static_cast<int>(kept_columns_.size());
  for (int c = 0; c < num_kept; ++c) triplets.emplace_back(c, c, 0.0);
  pattern_.resize(num_kept, num_kept);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  for (Block& block : blocks_) {
    const size_t n = block.kept.size();
    block.value_index.assign(n * n, -1);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        if (block.kept[i] >= block.kept[j]) {
          block.value_index[i * n + j] = ValueIndex(pattern_, block.kept[i], block.kept[j]);
        }
      }
    }
  }
}

void BlockNormalEquations::Assemble(const Eigen::VectorXd& block_weights,
                                    const std::vector<bool>& held,
                                    const std::vector<double>& held_values,
                                    Eigen::SparseMatrix<double>* normal,
                                    Eigen::VectorXd* rhs) const {
  *normal = pattern_;
  double* values = normal->valuePtr();
  rhs->setZero(pattern_.cols());
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const Block& block = blocks_[b];
    const double w = block_weights(b);
    const size_t n = block.kept.size();
    const bool holds = block.eliminated >= 0 && held[block.eliminated];
    // A free eliminated column with a zero Gram entry has no effect: its block is as if held at 0.
    const bool free = block.eliminated >= 0 && !holds && block.eliminated_gram > 0;
    const std::vector<double>& gram = free ? block.schur : block.gram;
    for (size_t i = 0; i < n; ++i) {
      // A held column's coupling moves to the right-hand side.
      if (holds) (*rhs)(block.kept[i]) -= w * block.coupling[i] * held_values[block.eliminated];
      for (size_t j = 0; j < n; ++j) {
        const int index = block.value_index[i * n + j];
        if (index >= 0) values[index] += w * gram[i * n + j];
      }
    }
  }
}

Eigen::VectorXd BlockNormalEquations::Expand(const Eigen::VectorXd& reduced,
                                             const std::vector<bool>& held,
                                             const std::vector<double>& held_values) const {
  Eigen::VectorXd full = Eigen::VectorXd::Zero(num_columns_);
  for (size_t r = 0; r < kept_columns_.size(); ++r) full(kept_columns_[r]) = reduced(r);
  for (size_t k = 0; k < eliminated_columns_.size(); ++k) {
    const int column = eliminated_columns_[k];
    if (held[k]) {
      full(column) = held_values[k];
      continue;
    }
    // A free column in no block, or with a zero Gram entry, is undetermined: zero.
    const int b = eliminated_block_[k];
    if (b < 0 || !(blocks_[b].eliminated_gram > 0)) continue;
    const Block& block = blocks_[b];
    double coupled = 0;
    for (size_t i = 0; i < block.kept.size(); ++i)
      coupled += block.coupling[i] * reduced(block.kept[i]);
    full(column) = -coupled / block.eliminated_gram;
  }
  return full;
}

}  // namespace ramap
