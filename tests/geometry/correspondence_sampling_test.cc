// The six-correspondence samplers: the paper's grid selection spreads its samples over the image
// and prefers confident matches; the baselines (random, ROI) do what their names say.
#include "ramap/geometry/correspondence_sampling.h"

#include <gtest/gtest.h>

#include <set>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// Matches on a regular lattice of a 640 x 480 image (the same pixel in both images), `per_cell`
// matches in each of the 8 x 6 cells, confidence = index (lower is better).
TwoViewCorrespondences Lattice(int per_cell) {
  TwoViewCorrespondences matches;
  matches.width1 = matches.width2 = 640;
  matches.height1 = matches.height2 = 480;
  matches.focal_length_px = 500;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 8; ++col) {
      for (int k = 0; k < per_cell; ++k) {
        const Eigen::Vector2d pixel(col * 80 + 10 + 20 * k, row * 80 + 40);
        matches.pixels1.push_back(pixel);
        matches.pixels2.push_back(pixel);
        matches.bearings1.push_back(
            Eigen::Vector3d(pixel.x() - 320, pixel.y() - 240, 500).normalized());
        matches.bearings2.push_back(matches.bearings1.back());
        matches.confidence.push_back(static_cast<double>(matches.confidence.size()));
      }
    }
  }
  return matches;
}

TEST(CorrespondenceSampling, GridCellsClampPixelsOutsideTheImage) {
  const ImageGrid grid{8, 6, 640, 480};
  EXPECT_EQ(grid.CellIndex({0, 0}), 0);
  EXPECT_EQ(grid.CellIndex({639, 479}), 47);
  EXPECT_EQ(grid.CellIndex({-5, 1000}), 40);
  EXPECT_EQ(grid.CellIndex({700, -1}), 7);
}

TEST(CorrespondenceSampling, GridSelectionSpreadsOverDistantCellsWithTheMostConfidentMatch) {
  const TwoViewCorrespondences matches = Lattice(3);
  const std::vector<int> scores = GridCorrespondenceScores(matches, 8, 6);
  for (const int score : scores) EXPECT_EQ(score, 3);
  const std::vector<int> six = SelectGridCorrespondences(matches, 8, 6, 6, 2);
  ASSERT_EQ(six.size(), 6u);
  const ImageGrid grid{8, 6, 640, 480};
  std::vector<int> cells;
  for (const int k : six) {
    // The most confident match of its cell: the first of the cell's three.
    EXPECT_EQ(k % 3, 0) << k;
    cells.push_back(grid.CellIndex(matches.pixels1[k]));
  }
  for (size_t a = 0; a < cells.size(); ++a) {
    for (size_t b = a + 1; b < cells.size(); ++b) {
      const int distance =
          std::max(std::abs(cells[a] % 8 - cells[b] % 8), std::abs(cells[a] / 8 - cells[b] / 8));
      EXPECT_GE(distance, 2) << cells[a] << " " << cells[b];
    }
  }
}

TEST(CorrespondenceSampling, RandomIsSeededAndDistinctRoiStaysInOneBlock) {
  const TwoViewCorrespondences matches = Lattice(1);
  const std::vector<int> a = SelectRandomCorrespondences(matches, 6, 7);
  EXPECT_EQ(a, SelectRandomCorrespondences(matches, 6, 7));
  EXPECT_EQ(std::set<int>(a.begin(), a.end()).size(), 6u);
  const std::vector<int> roi = SelectRoiCorrespondences(matches, 8, 6, 6);
  ASSERT_EQ(roi.size(), 6u);
  // One match per cell: a 3 x 3 block is the smallest that holds six.
  const ImageGrid grid{8, 6, 640, 480};
  int min_col = 8, max_col = -1, min_row = 6, max_row = -1;
  for (const int k : roi) {
    const int cell = grid.CellIndex(matches.pixels1[k]);
    min_col = std::min(min_col, cell % 8), max_col = std::max(max_col, cell % 8);
    min_row = std::min(min_row, cell / 8), max_row = std::max(max_row, cell / 8);
  }
  EXPECT_LE(max_col - min_col, 2);
  EXPECT_LE(max_row - min_row, 2);
}

TEST(CorrespondenceSampling, SampsonErrorsVanishOnTheEpipolarLines) {
  // A pure x translation: F = [t]x, epipolar lines are the rows.
  Eigen::Matrix3d F;
  F << 0, 0, 0, 0, 0, -1, 0, 1, 0;
  const std::vector<double> errors = SampsonErrors(F, {{10, 20}, {30, 40}}, {{50, 20}, {30, 43}});
  EXPECT_NEAR(errors[0], 0.0, 1e-12);
  EXPECT_NEAR(errors[1], 4.5, 1e-9);  // a 3 px row offset: 3^2 / 2
  EXPECT_EQ(SampsonErrors(Eigen::Matrix3d::Zero(), {{1, 2}}, {{3, 4}}), std::vector<double>{0.0});
}

TEST(CorrespondenceSampling, SamplerNamesRoundTrip) {
  for (const CorrespondenceSampler sampler :
       {CorrespondenceSampler::kGrid, CorrespondenceSampler::kRandom, CorrespondenceSampler::kRoi,
        CorrespondenceSampler::kRansac5}) {
    EXPECT_EQ(CorrespondenceSamplerFromName(CorrespondenceSamplerName(sampler)), sampler);
  }
  EXPECT_THROW(CorrespondenceSamplerFromName("best"), InputError);
}

}  // namespace
}  // namespace ramap
