#include "ramap/averaging/block_normal_equations.h"

#include <algorithm>
#include <cstdint>
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

// The lower triangle of the pattern of sum_b (block b's kept columns)^2, with every diagonal
// entry. The (column, row) keys are deduplicated as they come: blocks share most entries (the
// cameras of a track appear in many), and the blocks' triangles together were 12 million triplets
// (190 MiB, the translation averaging's peak) on a 4541-frame drive whose pattern has a tenth.
Eigen::SparseMatrix<double> LowerPattern(int num_columns, const std::vector<int>& kept,
                                         const std::vector<int>& column_begin) {
  std::vector<uint64_t> keys;
  const auto key = [](int row, int col) {
    return (static_cast<uint64_t>(col) << 32) | static_cast<uint32_t>(row);
  };
  const auto deduplicate = [&keys] {
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  };
  size_t deduplicate_at = size_t{1} << 22;
  for (int c = 0; c < num_columns; ++c) keys.push_back(key(c, c));
  for (size_t b = 0; b + 1 < column_begin.size(); ++b) {
    for (int i = column_begin[b]; i < column_begin[b + 1]; ++i) {
      for (int j = column_begin[b]; j <= i; ++j) keys.push_back(key(kept[i], kept[j]));
    }
    if (keys.size() >= deduplicate_at) {
      deduplicate();
      deduplicate_at = std::max(deduplicate_at, 2 * keys.size());
    }
  }
  deduplicate();
  Eigen::SparseMatrix<double> pattern(num_columns, num_columns);
  pattern.resizeNonZeros(static_cast<Eigen::Index>(keys.size()));
  int* outer = pattern.outerIndexPtr();
  std::fill(outer, outer + num_columns + 1, 0);
  for (size_t k = 0; k < keys.size(); ++k) {
    ++outer[(keys[k] >> 32) + 1];
    pattern.innerIndexPtr()[k] = static_cast<int>(keys[k] & 0xffffffffu);
    pattern.valuePtr()[k] = 0.0;
  }
  for (int c = 0; c < num_columns; ++c) outer[c + 1] += outer[c];
  return pattern;
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
  const int num_blocks = static_cast<int>(B.rows() / 3);
  column_begin_.reserve(num_blocks + 1);
  block_eliminated_.assign(num_blocks, -1);
  eliminated_vectors_.assign(eliminated_columns.size(), Eigen::Vector3d::Zero());
  for (int b = 0; b < num_blocks; ++b) {
    column_begin_.push_back(static_cast<int>(kept_.size()));
    for (const auto& [column, vector] : BlockColumns(rows, b)) {
      const int k = eliminated_index[column];
      if (k >= 0) {
        if (eliminated_block_[k] >= 0) {
          throw std::invalid_argument("BlockNormalEquations: an eliminated column in two blocks");
        }
        block_eliminated_[b] = k;
        eliminated_block_[k] = b;
        eliminated_vectors_[k] = vector;
        continue;
      }
      kept_.push_back(reduced_index[column]);
      vectors_.push_back(vector);
    }
  }
  column_begin_.push_back(static_cast<int>(kept_.size()));
  // Every diagonal entry, so that the pattern is complete even for columns no block touches.
  pattern_ = LowerPattern(static_cast<int>(kept_columns_.size()), kept_, column_begin_);
  value_begin_.reserve(num_blocks + 1);
  for (int b = 0; b < num_blocks; ++b) {
    value_begin_.push_back(static_cast<int>(value_index_.size()));
    for (int i = column_begin_[b]; i < column_begin_[b + 1]; ++i) {
      for (int j = column_begin_[b]; j <= i; ++j)
        value_index_.push_back(ValueIndex(pattern_, kept_[i], kept_[j]));
    }
  }
  value_begin_.push_back(static_cast<int>(value_index_.size()));
}

void BlockNormalEquations::Assemble(const Eigen::VectorXd& block_weights,
                                    const std::vector<bool>& held,
                                    const std::vector<double>& held_values,
                                    Eigen::SparseMatrix<double>* normal,
                                    Eigen::VectorXd* rhs) const {
  *normal = pattern_;
  double* values = normal->valuePtr();
  rhs->setZero(pattern_.cols());
  const int num_blocks = static_cast<int>(block_eliminated_.size());
  for (int b = 0; b < num_blocks; ++b) {
    const double w = block_weights(b);
    const int k = block_eliminated_[b];
    const bool holds = k >= 0 && held[k];
    // A free eliminated column with a zero Gram entry has no effect: its block is as if held at 0.
    const double eliminated_gram = k >= 0 ? eliminated_vectors_[k].squaredNorm() : 0.0;
    const bool free = k >= 0 && !holds && eliminated_gram > 0;
    const int first = column_begin_[b];
    const int* index = value_index_.data() + value_begin_[b];
    for (int i = first; i < column_begin_[b + 1]; ++i) {
      const double coupling_i = k >= 0 ? vectors_[i].dot(eliminated_vectors_[k]) : 0.0;
      // A held column's coupling moves to the right-hand side.
      if (holds) (*rhs)(kept_[i]) -= w * coupling_i * held_values[k];
      for (int j = first; j <= i; ++j) {
        double gram = vectors_[i].dot(vectors_[j]);
        // The Schur complement of the free column: its coupling removed.
        if (free) gram -= coupling_i * vectors_[j].dot(eliminated_vectors_[k]) / eliminated_gram;
        values[*index++] += w * gram;
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
    const double eliminated_gram = eliminated_vectors_[k].squaredNorm();
    if (b < 0 || !(eliminated_gram > 0)) continue;
    double coupled = 0;
    for (int i = column_begin_[b]; i < column_begin_[b + 1]; ++i)
      coupled += vectors_[i].dot(eliminated_vectors_[k]) * reduced(kept_[i]);
    full(column) = -coupled / eliminated_gram;
  }
  return full;
}

}  // namespace ramap
