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

}  // namespace

BlockNormalEquations::BlockNormalEquations(const Eigen::SparseMatrix<double>& B,
                                           const std::vector<int>& holdable_columns)
    : holdable_columns_(holdable_columns) {
  if (B.rows() % 3 != 0)
    throw std::invalid_argument("BlockNormalEquations: rows not in blocks of 3");
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = B;
  std::map<int, int> holdable_index;
  for (size_t k = 0; k < holdable_columns.size(); ++k) holdable_index[holdable_columns[k]] = k;

  std::vector<Eigen::Triplet<double>> triplets;
  blocks_.resize(B.rows() / 3);
  for (size_t b = 0; b < blocks_.size(); ++b) {
    std::map<int, Eigen::Vector3d> entries;  // column -> its 3 entries in the block
    for (int r = 0; r < 3; ++r) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, 3 * b + r); it;
           ++it) {
        auto [slot, inserted] = entries.emplace(it.col(), Eigen::Vector3d::Zero());
        slot->second(r) = it.value();
      }
    }
    Block& block = blocks_[b];
    std::vector<Eigen::Vector3d> vectors;
    for (const auto& [column, vector] : entries) {
      block.columns.push_back(column);
      vectors.push_back(vector);
      const auto hold = holdable_index.find(column);
      if (hold != holdable_index.end()) {
        block.holdable = hold->second;
        block.holdable_local = static_cast<int>(block.columns.size()) - 1;
      }
    }
    const size_t n = block.columns.size();
    block.gram.resize(n * n);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        block.gram[i * n + j] = vectors[i].dot(vectors[j]);
        if (block.columns[i] >= block.columns[j]) {
          triplets.emplace_back(block.columns[i], block.columns[j], 0.0);
        }
      }
    }
  }
  // Every diagonal entry, so that the pattern is complete even for columns no block touches.
  for (int c = 0; c < B.cols(); ++c) triplets.emplace_back(c, c, 0.0);
  pattern_.resize(B.cols(), B.cols());
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  for (Block& block : blocks_) {
    const size_t n = block.columns.size();
    block.value_index.assign(n * n, -1);
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        if (block.columns[i] >= block.columns[j]) {
          block.value_index[i * n + j] = ValueIndex(pattern_, block.columns[i], block.columns[j]);
        }
      }
    }
  }
  for (const int column : holdable_columns) {
    holdable_diagonal_index_.push_back(ValueIndex(pattern_, column, column));
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
    const size_t n = block.columns.size();
    const bool holds = block.holdable >= 0 && held[block.holdable];
    for (size_t i = 0; i < n; ++i) {
      if (holds && static_cast<int>(i) == block.holdable_local) continue;
      for (size_t j = 0; j < n; ++j) {
        if (holds && static_cast<int>(j) == block.holdable_local) {
          // A held column's coupling moves to the right-hand side.
          (*rhs)(block.columns[i]) -= w * block.gram[i * n + j] * held_values[block.holdable];
          continue;
        }
        const int index = block.value_index[i * n + j];
        if (index >= 0) values[index] += w * block.gram[i * n + j];
      }
    }
  }
  for (size_t k = 0; k < holdable_columns_.size(); ++k) {
    if (!held[k]) continue;
    values[holdable_diagonal_index_[k]] = 1.0;
    (*rhs)(holdable_columns_[k]) = held_values[k];
  }
}

}  // namespace ramap
