// Choosing the few correspondences from which a relative rotation is solved.
//
// The paper ("Pushing the Envelope of Rotation Averaging for Visual SLAM", Li, Yuan, Latecki,
// Ling, Sec. on relative rotation) selects six well-spread correspondences with a grid: both
// images are divided into the same grid of equal cells, a cell's correspondence score is the
// number of matches whose two keypoints fall into that same cell of both images, and the six
// best-scoring cells each contribute their most confident match. Random and ROI ("densest
// region") selection are the paper's ablation baselines.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "ramap/scene/view_graph.h"

namespace ramap {

enum class CorrespondenceSampler {
  kGrid,     // the paper's grid selection (default)
  kRandom,   // six random matches (seeded): ablation baseline
  kRoi,      // all six from the densest region of the grid: ablation baseline
  kRansac5,  // not a selection: RANSAC over 5-point essential matrices (baseline estimator)
};

// "grid", "random", "roi", "ransac5".
std::string CorrespondenceSamplerName(CorrespondenceSampler sampler);
// The sampler named `name`; throws InputError for an unknown name.
CorrespondenceSampler CorrespondenceSamplerFromName(const std::string& name);

// A uniform grid over one image: cell (col, row) has index row * cols + col.
struct ImageGrid {
  int cols = 8;
  int rows = 6;
  int width = 0;
  int height = 0;

  // Cell index of a pixel; positions outside the image are clamped to the border cells.
  int CellIndex(const Eigen::Vector2d& pixel) const;
};

// Per-cell correspondence scores of a pair: score[c] = number of matches whose keypoints fall into
// cell c of both images (both images use a cols x rows grid over their own size).
std::vector<int> GridCorrespondenceScores(const TwoViewCorrespondences& matches, int cols,
                                          int rows);

// The paper's grid selection. Cells are taken in order of decreasing score, greedily keeping a
// Chebyshev distance of at least `min_cell_distance` cells to the cells already taken; when that
// leaves fewer than `num_samples`, the distance is relaxed by one cell at a time down to 1
// (distinct cells). Each chosen cell contributes its same-cell match with the best (lowest)
// confidence. When fewer than `num_samples` cells score at all, the rest is filled with the most
// confident remaining matches, preferring matches whose cell in image 1 is not yet used and, among
// those, matches from the most populated cross-cell assignments (cell in image 1, cell in image 2).
// Returns match indices (fewer than num_samples only when there are fewer matches).
std::vector<int> SelectGridCorrespondences(const TwoViewCorrespondences& matches, int cols,
                                           int rows, int num_samples, int min_cell_distance);

// `num_samples` distinct matches drawn uniformly with a generator seeded by `seed`.
std::vector<int> SelectRandomCorrespondences(const TwoViewCorrespondences& matches, int num_samples,
                                             uint64_t seed);

// All samples from the densest region: the square block of k x k grid cells of image 1
// (k = 1, 2, ...) holding the most keypoints of matches, k grown until the block holds
// `num_samples` matches; inside it, the most confident matches.
std::vector<int> SelectRoiCorrespondences(const TwoViewCorrespondences& matches, int cols, int rows,
                                          int num_samples);

// Sampson errors (pixels^2) of matches under a fundamental matrix F (x2^T F x1 = 0): a per-match
// confidence for the selection, lower is better. Zero for every match when F is zero (unknown).
std::vector<double> SampsonErrors(const Eigen::Matrix3d& F,
                                  const std::vector<Eigen::Vector2d>& pixels1,
                                  const std::vector<Eigen::Vector2d>& pixels2);

}  // namespace ramap
