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

namespace ramap {

// The verified matches of one image pair, as the relative-pose estimator consumes them.
// Entry k of every vector describes the same match.
struct TwoViewCorrespondences {
  std::vector<Eigen::Vector3d> bearings1;  // unit, undistorted, in camera 1
  std::vector<Eigen::Vector3d> bearings2;  // unit, undistorted, in camera 2
  std::vector<Eigen::Vector2d> pixels1;    // keypoint positions in image 1 (for the grid)
  std::vector<Eigen::Vector2d> pixels2;    // keypoint positions in image 2
  int width1 = 0, height1 = 0;             // image sizes in pixels
  int width2 = 0, height2 = 0;
  // Mean focal length of the two cameras in pixels: turns the estimator's pixel thresholds into
  // angles. 0 (unknown) makes the estimator reject the pair.
  double focal_length_px = 0.0;
  // Per-match confidence, lower is better (e.g. Sampson error or descriptor distance); the caller
  // fills it. Empty means all matches are equally good (ties broken by index).
  std::vector<double> confidence;

  size_t size() const { return bearings1.size(); }
};

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
