#include "ramap/averaging/block_normal_equations.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "ramap/util/parallel.h"

namespace ramap {
namespace {

// The columns of block b of a row-major B with their 3 entries, by increasing column.
std::vector<std::pair<int, Eigen::Vector3d>> BlockColumns(
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& B, int b) {
  std::vector<std::pair<int, Eigen::Vector3d>> entries;
  for (int r = 0; r < 3; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B, 3 * b + r); it; ++it) {
      const auto slot = std::find_if(entries.begin(), entries.end(),
                                     [&](const auto& entry) { return entry.first == it.col(); });
      if (slot != entries.end()) {
        slot->second(r) = it.value();
        continue;
      }
      entries.emplace_back(static_cast<int>(it.col()), Eigen::Vector3d::Zero());
      entries.back().second(r) = it.value();
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  return entries;
}

}  // namespace

BlockNormalEquations::BlockNormalEquations(const Eigen::SparseMatrix<double, Eigen::RowMajor>& B,
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
  const int num_blocks = static_cast<int>(B.rows() / 3);
  column_begin_.reserve(num_blocks + 1);
  block_eliminated_.assign(num_blocks, -1);
  eliminated_vectors_.assign(eliminated_columns.size(), Eigen::Vector3d::Zero());
  for (int b = 0; b < num_blocks; ++b) {
    column_begin_.push_back(static_cast<int>(kept_.size()));
    for (const auto& [column, vector] : BlockColumns(B, b)) {
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
  BuildPattern(static_cast<int>(kept_columns_.size()));
}

// Column by column: the rows below the diagonal that share a block with the column, found through
// the blocks that hold it (a stamp per row instead of a sort of every block's entries: the blocks
// share most entries, so their triangles together are far larger than the pattern on a drive),
// and each block's entries pointed at their slots as the column is laid out.
void BlockNormalEquations::BuildPattern(int num_columns) {
  const int num_blocks = static_cast<int>(column_begin_.size()) - 1;
  // Each block's lower triangle, row by row, as value_index_ lays it out.
  value_begin_.assign(num_blocks + 1, 0);
  for (int b = 0; b < num_blocks; ++b) {
    const int n = column_begin_[b + 1] - column_begin_[b];
    value_begin_[b + 1] = value_begin_[b] + n * (n + 1) / 2;
  }
  value_index_.assign(value_begin_.back(), -1);
  // The (block, local index) of every kept column's appearances.
  std::vector<int> appearances_begin(num_columns + 1, 0);
  for (const int column : kept_) ++appearances_begin[column + 1];
  for (int c = 0; c < num_columns; ++c) appearances_begin[c + 1] += appearances_begin[c];
  std::vector<std::pair<int, int>> appearances(kept_.size());
  std::vector<int> fill = appearances_begin;
  for (int b = 0; b < num_blocks; ++b) {
    for (int i = column_begin_[b]; i < column_begin_[b + 1]; ++i)
      appearances[fill[kept_[i]]++] = {b, i - column_begin_[b]};
  }
  std::vector<int> outer(num_columns + 1, 0);
  std::vector<int> inner;
  std::vector<int> stamp(num_columns, -1);
  std::vector<int> slot(num_columns, -1);
  std::vector<int> rows;
  for (int c = 0; c < num_columns; ++c) {
    rows.assign(1, c);  // every diagonal entry, even of a column no block touches
    stamp[c] = c;
    for (int a = appearances_begin[c]; a < appearances_begin[c + 1]; ++a) {
      const auto [b, local] = appearances[a];
      for (int i = column_begin_[b] + local; i < column_begin_[b + 1]; ++i) {
        if (stamp[kept_[i]] != c) stamp[kept_[i]] = c, rows.push_back(kept_[i]);
      }
    }
    std::sort(rows.begin(), rows.end());
    for (size_t r = 0; r < rows.size(); ++r) slot[rows[r]] = static_cast<int>(inner.size() + r);
    inner.insert(inner.end(), rows.begin(), rows.end());
    outer[c + 1] = static_cast<int>(inner.size());
    // Entry (i, local) of block b, i >= local, sits at row i, column `local` of its triangle.
    for (int a = appearances_begin[c]; a < appearances_begin[c + 1]; ++a) {
      const auto [b, local] = appearances[a];
      for (int i = local; i < column_begin_[b + 1] - column_begin_[b]; ++i) {
        value_index_[value_begin_[b] + i * (i + 1) / 2 + local] = slot[kept_[column_begin_[b] + i]];
      }
    }
  }
  pattern_.resize(num_columns, num_columns);
  pattern_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), pattern_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), pattern_.innerIndexPtr());
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + inner.size(), 0.0);
}

void BlockNormalEquations::AddBlocks(int begin, int end, const Eigen::VectorXd& block_weights,
                                     const std::vector<bool>& held,
                                     const std::vector<double>& held_values, double* values,
                                     double* rhs) const {
  for (int b = begin; b < end; ++b) {
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
      if (holds) rhs[kept_[i]] -= w * coupling_i * held_values[k];
      for (int j = first; j <= i; ++j) {
        double gram = vectors_[i].dot(vectors_[j]);
        // The Schur complement of the free column: its coupling removed.
        if (free) gram -= coupling_i * vectors_[j].dot(eliminated_vectors_[k]) / eliminated_gram;
        values[*index++] += w * gram;
      }
    }
  }
}

void BlockNormalEquations::Assemble(const Eigen::VectorXd& block_weights,
                                    const std::vector<bool>& held,
                                    const std::vector<double>& held_values,
                                    Eigen::SparseMatrix<double>* normal, Eigen::VectorXd* rhs,
                                    int num_threads) const {
  *normal = pattern_;
  rhs->setZero(pattern_.cols());
  const size_t num_blocks = block_eliminated_.size();
  // A share smaller than this costs more in its own copy of the values than it saves.
  constexpr size_t kMinBlocksPerShare = 2000;
  const size_t num_shares = NumShares(num_blocks, num_threads, kMinBlocksPerShare);
  // Each share but the first sums into values of its own, added to the first's in order after.
  const Eigen::Index num_values = pattern_.nonZeros();
  std::vector<Eigen::VectorXd> values(num_shares - 1, Eigen::VectorXd::Zero(num_values));
  std::vector<Eigen::VectorXd> rhss(num_shares - 1, Eigen::VectorXd::Zero(pattern_.cols()));
  ForEachShare(num_blocks, num_shares, [&](size_t share, size_t begin, size_t end) {
    double* share_values = share == 0 ? normal->valuePtr() : values[share - 1].data();
    double* share_rhs = share == 0 ? rhs->data() : rhss[share - 1].data();
    AddBlocks(static_cast<int>(begin), static_cast<int>(end), block_weights, held, held_values,
              share_values, share_rhs);
  });
  Eigen::Map<Eigen::VectorXd> first(normal->valuePtr(), num_values);
  for (size_t share = 1; share < num_shares; ++share) {
    first += values[share - 1];
    *rhs += rhss[share - 1];
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
