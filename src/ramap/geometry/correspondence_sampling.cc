#include "ramap/geometry/correspondence_sampling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <utility>

#include "ramap/util/error.h"

namespace ramap {
namespace {

double Confidence(const TwoViewCorrespondences& matches, int k) {
  return matches.confidence.empty() ? 0.0 : matches.confidence[k];
}

// Orders match indices by confidence (lower first), ties by index so results are deterministic.
void SortByConfidence(const TwoViewCorrespondences& matches, std::vector<int>* indices) {
  std::stable_sort(indices->begin(), indices->end(),
                   [&](int a, int b) { return Confidence(matches, a) < Confidence(matches, b); });
}

int ClampCell(double v, double size, int num) {
  if (!(size > 0) || !std::isfinite(v)) return 0;
  const int c = static_cast<int>(std::floor(v / size * num));
  return std::clamp(c, 0, num - 1);
}

// The matches not yet used, in the order that fills a grid selection: from the most populated
// (image-1 cell, image-2 cell) assignments first, then the most confident.
std::vector<int> FillOrder(const TwoViewCorrespondences& matches, const std::vector<int>& cell1,
                           const std::vector<int>& cell2, const std::vector<bool>& used_match) {
  const int n = static_cast<int>(cell1.size());
  std::map<std::pair<int, int>, int> assignment_count;
  for (int k = 0; k < n; ++k) ++assignment_count[{cell1[k], cell2[k]}];
  // Each match's count looked up once, not at every comparison of the sort.
  std::vector<int> count_of_match(n);
  for (int k = 0; k < n; ++k) count_of_match[k] = assignment_count[{cell1[k], cell2[k]}];
  std::vector<int> rest;
  for (int k = 0; k < n; ++k) {
    if (!used_match[k]) rest.push_back(k);
  }
  SortByConfidence(matches, &rest);
  std::stable_sort(rest.begin(), rest.end(),
                   [&](int a, int b) { return count_of_match[a] > count_of_match[b]; });
  return rest;
}

}  // namespace

std::string CorrespondenceSamplerName(CorrespondenceSampler sampler) {
  switch (sampler) {
    case CorrespondenceSampler::kGrid:
      return "grid";
    case CorrespondenceSampler::kRandom:
      return "random";
    case CorrespondenceSampler::kRoi:
      return "roi";
    case CorrespondenceSampler::kRansac5:
      return "ransac5";
  }
  return "unknown";
}

CorrespondenceSampler CorrespondenceSamplerFromName(const std::string& name) {
  for (CorrespondenceSampler s : {CorrespondenceSampler::kGrid, CorrespondenceSampler::kRandom,
                                  CorrespondenceSampler::kRoi, CorrespondenceSampler::kRansac5}) {
    if (CorrespondenceSamplerName(s) == name) return s;
  }
  throw InputError("--RelativePose.sampler",
                   "unknown sampler '" + name + "' (expected grid, random, roi or ransac5)");
}

int ImageGrid::CellIndex(const Eigen::Vector2d& pixel) const {
  return ClampCell(pixel.y(), height, rows) * cols + ClampCell(pixel.x(), width, cols);
}

std::vector<int> GridCorrespondenceScores(const TwoViewCorrespondences& matches, int cols,
                                          int rows) {
  const ImageGrid grid1{cols, rows, matches.width1, matches.height1};
  const ImageGrid grid2{cols, rows, matches.width2, matches.height2};
  std::vector<int> scores(cols * rows, 0);
  for (size_t k = 0; k < matches.size(); ++k) {
    const int c1 = grid1.CellIndex(matches.pixels1[k]);
    if (c1 == grid2.CellIndex(matches.pixels2[k])) ++scores[c1];
  }
  return scores;
}

std::vector<int> SelectGridCorrespondences(const TwoViewCorrespondences& matches, int cols,
                                           int rows, int num_samples, int min_cell_distance) {
  const ImageGrid grid1{cols, rows, matches.width1, matches.height1};
  const ImageGrid grid2{cols, rows, matches.width2, matches.height2};
  const int num_cells = cols * rows;
  const int n = static_cast<int>(matches.size());

  // Same-cell matches per cell, most confident first.
  std::vector<int> cell1(n), cell2(n);
  std::vector<std::vector<int>> same_cell(num_cells);
  for (int k = 0; k < n; ++k) {
    cell1[k] = grid1.CellIndex(matches.pixels1[k]);
    cell2[k] = grid2.CellIndex(matches.pixels2[k]);
    if (cell1[k] == cell2[k]) same_cell[cell1[k]].push_back(k);
  }
  std::vector<int> scored_cells;
  for (int c = 0; c < num_cells; ++c) {
    if (same_cell[c].empty()) continue;
    SortByConfidence(matches, &same_cell[c]);
    scored_cells.push_back(c);
  }
  std::stable_sort(scored_cells.begin(), scored_cells.end(),
                   [&](int a, int b) { return same_cell[a].size() > same_cell[b].size(); });

  // Greedy spread: strict distance first, relaxed while too few cells were taken.
  std::vector<int> chosen_cells;
  std::vector<bool> taken(num_cells, false);
  auto far_enough = [&](int c, int distance) {
    for (int other : chosen_cells) {
      const int dc = std::abs(c % cols - other % cols);
      const int dr = std::abs(c / cols - other / cols);
      if (std::max(dc, dr) < distance) return false;
    }
    return true;
  };
  for (int distance = std::max(1, min_cell_distance);
       distance >= 1 && static_cast<int>(chosen_cells.size()) < num_samples; --distance) {
    for (int c : scored_cells) {
      if (static_cast<int>(chosen_cells.size()) >= num_samples) break;
      if (taken[c] || !far_enough(c, distance)) continue;
      taken[c] = true;
      chosen_cells.push_back(c);
    }
  }

  std::vector<int> selected;
  std::vector<bool> used_match(n, false);
  std::vector<bool> used_cell1(num_cells, false);
  for (int c : chosen_cells) {
    const int k = same_cell[c].front();
    selected.push_back(k);
    used_match[k] = true;
    used_cell1[c] = true;
  }
  if (static_cast<int>(selected.size()) >= num_samples) return selected;

  // Fill: matches from unused image-1 cells first, then any.
  const std::vector<int> rest = FillOrder(matches, cell1, cell2, used_match);
  for (bool require_new_cell : {true, false}) {
    for (const int k : rest) {
      if (static_cast<int>(selected.size()) >= num_samples) return selected;
      if (used_match[k] || (require_new_cell && used_cell1[cell1[k]])) continue;
      selected.push_back(k);
      used_match[k] = true;
      used_cell1[cell1[k]] = true;
    }
  }
  return selected;
}

std::vector<int> SelectRandomCorrespondences(const TwoViewCorrespondences& matches, int num_samples,
                                             uint64_t seed) {
  std::vector<int> indices(matches.size());
  std::iota(indices.begin(), indices.end(), 0);
  std::mt19937_64 rng(seed);
  const int m = std::min<int>(num_samples, static_cast<int>(indices.size()));
  // Partial Fisher-Yates: the first m entries become a uniform sample.
  for (int i = 0; i < m; ++i) {
    std::uniform_int_distribution<int> pick(i, static_cast<int>(indices.size()) - 1);
    std::swap(indices[i], indices[pick(rng)]);
  }
  indices.resize(m);
  return indices;
}

std::vector<int> SelectRoiCorrespondences(const TwoViewCorrespondences& matches, int cols, int rows,
                                          int num_samples) {
  const ImageGrid grid1{cols, rows, matches.width1, matches.height1};
  const int n = static_cast<int>(matches.size());
  std::vector<int> col(n), row(n);
  for (int k = 0; k < n; ++k) {
    const int c = grid1.CellIndex(matches.pixels1[k]);
    col[k] = c % cols;
    row[k] = c / cols;
  }
  const int target = std::min(num_samples, n);
  for (int block = 1; block <= std::max(cols, rows); ++block) {
    std::vector<int> best;
    for (int r0 = 0; r0 + block <= std::max(rows, block); ++r0) {
      for (int c0 = 0; c0 + block <= std::max(cols, block); ++c0) {
        std::vector<int> inside;
        for (int k = 0; k < n; ++k) {
          if (col[k] >= c0 && col[k] < c0 + block && row[k] >= r0 && row[k] < r0 + block) {
            inside.push_back(k);
          }
        }
        if (inside.size() > best.size()) best = std::move(inside);
      }
    }
    if (static_cast<int>(best.size()) >= target) {
      SortByConfidence(matches, &best);
      best.resize(target);
      return best;
    }
  }
  return {};
}

std::vector<double> SampsonErrors(const Eigen::Matrix3d& F,
                                  const std::vector<Eigen::Vector2d>& pixels1,
                                  const std::vector<Eigen::Vector2d>& pixels2) {
  std::vector<double> errors(pixels1.size(), 0.0);
  if (F.isZero()) return errors;
  for (size_t k = 0; k < pixels1.size(); ++k) {
    const Eigen::Vector3d x1 = pixels1[k].homogeneous(), x2 = pixels2[k].homogeneous();
    const Eigen::Vector3d Fx1 = F * x1, Ftx2 = F.transpose() * x2;
    const double numerator = x2.dot(Fx1);
    const double denominator = Fx1.head<2>().squaredNorm() + Ftx2.head<2>().squaredNorm();
    errors[k] =
        denominator > 0 ? numerator * numerator / denominator : std::numeric_limits<double>::max();
  }
  return errors;
}

}  // namespace ramap
