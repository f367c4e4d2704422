#include "ramap/geometry/relative_pose.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <set>

#include "ramap/geometry/correspondence_sampling.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
constexpr int kWidth = 640, kHeight = 480;
constexpr double kFocal = 500, kCx = 320, kCy = 240;

Eigen::Vector3d PixelToBearing(const Eigen::Vector2d& p) {
  return Eigen::Vector3d((p.x() - kCx) / kFocal, (p.y() - kCy) / kFocal, 1).normalized();
}

Eigen::Vector2d Project(const Eigen::Vector3d& x) {
  return Eigen::Vector2d(kFocal * x.x() / x.z() + kCx, kFocal * x.y() / x.z() + kCy);
}

bool InImage(const Eigen::Vector2d& p) {
  return p.x() >= 0 && p.x() < kWidth && p.y() >= 0 && p.y() < kHeight;
}

// A synthetic pair: camera 1 is the world frame, camera 2 has pose x2 = R x1 + t, i.e. the
// relative pose cam2_from_cam1 the estimator should return.
struct SyntheticPair {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;  // true cam2_from_cam1 translation (not unit)
  TwoViewCorrespondences matches;
};

// Points are drawn by pixel in image 1 within [x0, x1) x [y0, y1) and a depth in [4, 12], kept when
// visible in image 2. `noise_px` Gaussian noise is added to both pixels before making bearings.
SyntheticPair MakePair(const Eigen::Matrix3d& R, const Eigen::Vector3d& center2, int num_points,
                       double noise_px, uint64_t seed,
                       Eigen::AlignedBox2d region1 = Eigen::AlignedBox2d(
                           Eigen::Vector2d(0, 0), Eigen::Vector2d(kWidth, kHeight))) {
  SyntheticPair pair;
  pair.R = R;
  pair.t = -R * center2;
  pair.matches.width1 = pair.matches.width2 = kWidth;
  pair.matches.height1 = pair.matches.height2 = kHeight;
  pair.matches.focal_length_px = kFocal;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> noise(0, noise_px);
  int attempts = 0;
  while (static_cast<int>(pair.matches.size()) < num_points && ++attempts < 100000) {
    const Eigen::Vector2d p1 =
        region1.min() +
        (region1.max() - region1.min()).cwiseProduct(Eigen::Vector2d(u01(rng), u01(rng)));
    const double depth = 4 + 8 * u01(rng);
    const Eigen::Vector3d x1 =
        depth * Eigen::Vector3d((p1.x() - kCx) / kFocal, (p1.y() - kCy) / kFocal, 1);
    const Eigen::Vector3d x2 = R * x1 + pair.t;
    if (x2.z() < 0.5) continue;
    const Eigen::Vector2d p2 = Project(x2);
    if (!InImage(p2)) continue;
    Eigen::Vector2d q1 = p1, q2 = p2;
    if (noise_px > 0) {
      q1 += Eigen::Vector2d(noise(rng), noise(rng));
      q2 += Eigen::Vector2d(noise(rng), noise(rng));
    }
    pair.matches.pixels1.push_back(q1);
    pair.matches.pixels2.push_back(q2);
    pair.matches.bearings1.push_back(PixelToBearing(q1));
    pair.matches.bearings2.push_back(PixelToBearing(q2));
    pair.matches.confidence.push_back(u01(rng));
  }
  return pair;
}

Eigen::Matrix3d Rotation(double angle_deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle_deg / kRadToDeg, axis.normalized()).toRotationMatrix();
}

double RotationErrorDeg(const RelativePoseEstimate& estimate, const Eigen::Matrix3d& R) {
  const Eigen::Matrix3d delta = estimate.rotation.toRotationMatrix() * R.transpose();
  return Eigen::AngleAxisd(delta).angle() * kRadToDeg;
}

double TranslationErrorDeg(const RelativePoseEstimate& estimate, const Eigen::Vector3d& t) {
  const Eigen::Vector3d a = estimate.translation.normalized(), b = t.normalized();
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kRadToDeg;
}

struct Motion {
  const char* name;
  Eigen::Matrix3d R;
  Eigen::Vector3d center2;
};

std::vector<Motion> Motions() {
  return {
      {"sideways", Rotation(4, Eigen::Vector3d(0, 1, 0)), Eigen::Vector3d(1.0, 0, 0)},
      {"forward", Rotation(3, Eigen::Vector3d(1, 0.5, 0)), Eigen::Vector3d(0.05, 0, 1.5)},
      {"general", Rotation(12, Eigen::Vector3d(0.3, -1, 0.2)), Eigen::Vector3d(0.6, -0.3, 0.8)},
  };
}

void ExpectExactRecovery(CorrespondenceSampler sampler) {
  for (const Motion& motion : Motions()) {
    SCOPED_TRACE(std::string(motion.name) + " / " + CorrespondenceSamplerName(sampler));
    const SyntheticPair pair = MakePair(motion.R, motion.center2, 200, 0, 7);
    ASSERT_EQ(pair.matches.size(), 200u);
    RelativePoseOptions options;
    options.sampler = sampler;
    options.seed = 3;
    const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, options);
    ASSERT_TRUE(estimate.success) << estimate.reason;
    EXPECT_LT(RotationErrorDeg(estimate, pair.R), 1e-6);
    EXPECT_LT(TranslationErrorDeg(estimate, pair.t), 1e-5);
    EXPECT_NEAR(estimate.translation.norm(), 1.0, 1e-12);
    EXPECT_EQ(estimate.num_inliers, 200);
    EXPECT_EQ(estimate.flags, kRelativePoseNone);
    EXPECT_DOUBLE_EQ(estimate.cheirality_ratio, 1.0);
    EXPECT_TRUE(estimate.reason.empty());
    EXPECT_EQ(estimate.rejection, RelativePoseRejection::kNone);
  }
}

TEST(RelativePoseTest, GridRecoversExactPose) { ExpectExactRecovery(CorrespondenceSampler::kGrid); }
TEST(RelativePoseTest, RandomRecoversExactPose) {
  ExpectExactRecovery(CorrespondenceSampler::kRandom);
}
TEST(RelativePoseTest, RoiRecoversExactPose) { ExpectExactRecovery(CorrespondenceSampler::kRoi); }
TEST(RelativePoseTest, Ransac5RecoversExactPose) {
  ExpectExactRecovery(CorrespondenceSampler::kRansac5);
}

TEST(RelativePoseTest, PureRotationIsFlagged) {
  const Eigen::Matrix3d R = Rotation(8, Eigen::Vector3d(0.2, 1, -0.1));
  const SyntheticPair pair = MakePair(R, Eigen::Vector3d::Zero(), 150, 0, 11);
  for (CorrespondenceSampler sampler :
       {CorrespondenceSampler::kGrid, CorrespondenceSampler::kRansac5}) {
    RelativePoseOptions options;
    options.sampler = sampler;
    const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, options);
    ASSERT_TRUE(estimate.success) << estimate.reason;
    EXPECT_TRUE(estimate.flags & kRelativePosePureRotation);
    EXPECT_LT(RotationErrorDeg(estimate, R), 1e-6);
    EXPECT_EQ(estimate.translation, Eigen::Vector3d::Zero());
    EXPECT_EQ(estimate.num_inliers, 150);
  }
}

TEST(RelativePoseTest, GridWithOnePixelNoise) {
  for (const Motion& motion : Motions()) {
    SCOPED_TRACE(motion.name);
    for (uint64_t seed = 1; seed <= 5; ++seed) {
      const SyntheticPair pair = MakePair(motion.R, motion.center2, 300, 1.0, seed);
      const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
      ASSERT_TRUE(estimate.success) << estimate.reason;
      EXPECT_LT(RotationErrorDeg(estimate, pair.R), 0.5) << "seed " << seed;
      EXPECT_LT(TranslationErrorDeg(estimate, pair.t), 10.0) << "seed " << seed;
      EXPECT_GT(estimate.num_inliers, 270);
    }
  }
}

TEST(RelativePoseTest, GridIgnoresLowConfidenceOutliers) {
  const Motion motion = Motions()[2];
  SyntheticPair pair = MakePair(motion.R, motion.center2, 200, 0, 5);
  // 25% of the matches get a wrong partner; the caller rates them badly (high score).
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<size_t> pick(0, pair.matches.size() - 1);
  std::set<size_t> outliers;
  while (outliers.size() < 50) {
    const size_t a = pick(rng), b = pick(rng);
    if (a == b || outliers.count(a)) continue;
    pair.matches.bearings2[a] = pair.matches.bearings2[b];
    pair.matches.pixels2[a] = pair.matches.pixels2[b];
    pair.matches.confidence[a] = 10.0;
    outliers.insert(a);
  }
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  ASSERT_TRUE(estimate.success) << estimate.reason;
  EXPECT_LT(RotationErrorDeg(estimate, pair.R), 1e-6);
  EXPECT_LT(TranslationErrorDeg(estimate, pair.t), 1e-5);
  for (int k : estimate.inliers) EXPECT_EQ(outliers.count(k), 0u) << "outlier " << k << " kept";
  EXPECT_GE(estimate.num_inliers, 140);
}

// The grid takes the most confident match of each chosen cell; when one of those six is wrong
// (here: its bearing in image 2 is another match's, its keypoints unchanged so that the grid still
// picks it), the candidates of the five-point solver on the other five must still recover the
// pose, with either five-point solver.
TEST(RelativePoseTest, OneBadMatchAmongTheSixIsOutvoted) {
  for (const bool nister_five_point : {false, true}) {
    SCOPED_TRACE(nister_five_point ? "Nister five-point" : "Kneip five-point");
    std::vector<Motion> motions = Motions();
    // A large roll too: a candidate rotation of the wrong handedness (R^T for R) is then far from
    // the truth, not a start the refinement can still repair.
    motions.push_back({"roll", Rotation(35, Eigen::Vector3d(0.1, 0.2, 1)), {0.5, 0.2, 0.3}});
    for (const Motion& motion : motions) {
      SCOPED_TRACE(motion.name);
      SyntheticPair pair = MakePair(motion.R, motion.center2, 200, 0, 11);
      RelativePoseOptions options;
      options.nister_five_point = nister_five_point;
      const std::vector<int> six = SelectGridCorrespondences(
          pair.matches, options.grid_cols, options.grid_rows, 6, options.min_cell_distance);
      ASSERT_EQ(six.size(), 6u);
      const int bad = six[2], partner = six[5];
      pair.matches.bearings2[bad] = pair.matches.bearings2[partner];
      const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, options);
      EXPECT_TRUE(estimate.success) << estimate.reason;
      if (!estimate.success) continue;
      EXPECT_LT(RotationErrorDeg(estimate, pair.R), 1e-6);
      EXPECT_LT(TranslationErrorDeg(estimate, pair.t), 1e-5);
      EXPECT_EQ(std::count(estimate.inliers.begin(), estimate.inliers.end(), bad), 0);
      EXPECT_EQ(estimate.num_inliers, 199);
    }
  }
}

// Stopping the five-point solves once a candidate explains 90% of the first round's matches (the
// default) must cost no accuracy against solving every candidate: noisy pairs with 5% of their
// matches wrong, few enough that a correct candidate is confident. (A wrong match can still be
// among the grid's six when it is alone in its cell; a clean five with noise then does not always
// give a good root, and both fail alike: such pairs are counted, not compared. The noise, 0.5 px,
// is low enough for the default error bound to let a candidate be confident.)
TEST(RelativePoseTest, ConfidentStopIsAsAccurateAsEveryCandidate) {
  RelativePoseOptions every_candidate;
  every_candidate.confident_inlier_ratio = 2;
  int compared = 0, total = 0;
  for (const Motion& motion : Motions()) {
    SCOPED_TRACE(motion.name);
    for (uint64_t seed = 1; seed <= 6; ++seed) {
      SyntheticPair pair = MakePair(motion.R, motion.center2, 300, 0.5, seed);
      const size_t n = pair.matches.size();
      for (size_t k = 0; k < n; k += 20) {
        const size_t other = (k + n / 2) % n;
        pair.matches.pixels2[k] = pair.matches.pixels2[other];
        pair.matches.bearings2[k] = pair.matches.bearings2[other];
        pair.matches.confidence[k] = 2;  // an error: ranked last in its cell
      }
      const RelativePoseEstimate stopped = EstimateRelativePose(pair.matches, {});
      const RelativePoseEstimate every = EstimateRelativePose(pair.matches, every_candidate);
      ++total;
      if (!every.success) continue;
      ++compared;
      ASSERT_TRUE(stopped.success) << stopped.reason << ", seed " << seed;
      EXPECT_LT(RotationErrorDeg(stopped, pair.R), RotationErrorDeg(every, pair.R) + 0.02)
          << "seed " << seed;
      EXPECT_LT(RotationErrorDeg(stopped, pair.R), 0.5) << "seed " << seed;
      EXPECT_NEAR(stopped.num_inliers, every.num_inliers, 3) << "seed " << seed;
    }
  }
  EXPECT_GE(compared, total - 2);
}

// A root solved from five matches with 0.5 px noise misses the error bound (0.7-1.1 px RMS);
// refined once on the matches it explains it meets it, and the first subset ends the search. In a
// view the options call narrow, the narrow bound applies instead: at 0 px no candidate is confident
// and all six subsets are solved.
TEST(RelativePoseTest, ARefinedFirstCandidateEndsTheFivePointSolves) {
  RelativePoseOptions narrow;
  narrow.confident_narrow_view_deg = 90;
  narrow.confident_narrow_view_rms_error_px = 0;
  int num_pairs = 0, num_stopped_at_first = 0;
  for (const Motion& motion : Motions()) {
    SCOPED_TRACE(motion.name);
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      const SyntheticPair pair = MakePair(motion.R, motion.center2, 300, 0.5, seed);
      const RelativePoseEstimate stopped = EstimateRelativePose(pair.matches, {});
      const RelativePoseEstimate every = EstimateRelativePose(pair.matches, narrow);
      ASSERT_TRUE(stopped.success && every.success) << "seed " << seed;
      EXPECT_EQ(every.num_five_point_subsets, 6) << "seed " << seed;
      EXPECT_LT(RotationErrorDeg(stopped, pair.R), RotationErrorDeg(every, pair.R) + 0.02);
      ++num_pairs;
      num_stopped_at_first += stopped.num_five_point_subsets == 1;
    }
  }
  EXPECT_GE(num_stopped_at_first, num_pairs * 3 / 4);
}

TEST(RelativePoseTest, RejectsFewerThanSix) {
  const Motion motion = Motions()[0];
  SyntheticPair pair = MakePair(motion.R, motion.center2, 5, 0, 1);
  RelativePoseOptions options;
  options.min_num_inliers = 6;
  RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, options);
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("only 5 matches"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kTooFewMatches);
  // And fewer than COLMAP's 15 with the defaults.
  pair = MakePair(motion.R, motion.center2, 12, 0, 1);
  estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_FALSE(estimate.reason.empty());
}

TEST(RelativePoseTest, RejectsAllInOneCell) {
  const Motion motion = Motions()[0];
  const SyntheticPair pair =
      MakePair(motion.R, motion.center2, 40, 0, 2,
               Eigen::AlignedBox2d(Eigen::Vector2d(405, 250), Eigen::Vector2d(475, 315)));
  ASSERT_EQ(pair.matches.size(), 40u);
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("one grid cell"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kTooLittleSpread);
}

TEST(RelativePoseTest, RejectsCollinearPoints) {
  // Points on one 3D line project to one line in both images.
  const Motion motion = Motions()[2];
  SyntheticPair pair;
  pair.matches.width1 = pair.matches.width2 = kWidth;
  pair.matches.height1 = pair.matches.height2 = kHeight;
  pair.matches.focal_length_px = kFocal;
  const Eigen::Vector3d t = -motion.R * motion.center2;
  for (int k = 0; k < 30; ++k) {
    const Eigen::Vector3d x1 =
        Eigen::Vector3d(-1.5, -0.5, 6) + 0.1 * k * Eigen::Vector3d(1, 0.3, 0.2);
    const Eigen::Vector3d x2 = motion.R * x1 + t;
    pair.matches.pixels1.push_back(Project(x1));
    pair.matches.pixels2.push_back(Project(x2));
    pair.matches.bearings1.push_back(x1.normalized());
    pair.matches.bearings2.push_back(x2.normalized());
  }
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("collinear"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kTooLittleSpread);
}

TEST(RelativePoseTest, RejectsUnknownFocalLength) {
  const Motion motion = Motions()[0];
  SyntheticPair pair = MakePair(motion.R, motion.center2, 100, 0, 4);
  pair.matches.focal_length_px = 0;
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("focal length unknown"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kUnknownFocalLength);
}

TEST(RelativePoseTest, RejectsIdenticalImages) {
  SyntheticPair pair = MakePair(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 100, 0, 4);
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("no motion"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kNoMotion);
}

TEST(RelativePoseTest, RejectsNaNInput) {
  const Motion motion = Motions()[1];
  SyntheticPair pair = MakePair(motion.R, motion.center2, 100, 0, 4);
  pair.matches.bearings2[17].y() = std::numeric_limits<double>::quiet_NaN();
  RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("non-finite"), std::string::npos) << estimate.reason;
  EXPECT_TRUE(estimate.rotation.coeffs().allFinite());

  pair = MakePair(motion.R, motion.center2, 100, 0, 4);
  pair.matches.pixels1[3].x() = std::numeric_limits<double>::infinity();
  estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("non-finite"), std::string::npos) << estimate.reason;
}

TEST(RelativePoseTest, RejectsInconsistentInput) {
  const Motion motion = Motions()[1];
  SyntheticPair pair = MakePair(motion.R, motion.center2, 100, 0, 4);
  pair.matches.pixels2.pop_back();
  const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, {});
  EXPECT_FALSE(estimate.success);
  EXPECT_NE(estimate.reason.find("inconsistent"), std::string::npos) << estimate.reason;
  EXPECT_EQ(estimate.rejection, RelativePoseRejection::kInvalidInput);
}

TEST(RelativePoseTest, OptionsCheck) {
  RelativePoseOptions options;
  EXPECT_NO_THROW(options.Check());
  options.min_num_inliers = 5;
  EXPECT_THROW(options.Check(), InputError);
  options = {};
  options.max_epipolar_error_px = 0;
  EXPECT_THROW(options.Check(), InputError);
  options = {};
  options.grid_rows = 0;
  EXPECT_THROW(options.Check(), InputError);
  options = {};
  options.confident_inlier_ratio = -0.1;
  EXPECT_THROW(options.Check(), InputError);
  EXPECT_EQ(CorrespondenceSamplerFromName("roi"), CorrespondenceSampler::kRoi);
  EXPECT_EQ(CorrespondenceSamplerName(CorrespondenceSamplerFromName("ransac5")), "ransac5");
  EXPECT_THROW(CorrespondenceSamplerFromName("sift"), InputError);
}

// A hand-made layout: cell c of an 8 x 6 grid over 640 x 480 (80 px cells) is at col c % 8,
// row c / 8.
Eigen::Vector2d CellCenter(int cell, double dx = 0) {
  return Eigen::Vector2d(80 * (cell % 8) + 40 + dx, 80 * (cell / 8) + 40);
}

void AddMatch(TwoViewCorrespondences* m, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
              double confidence) {
  m->pixels1.push_back(p1);
  m->pixels2.push_back(p2);
  m->bearings1.push_back(PixelToBearing(p1));
  m->bearings2.push_back(PixelToBearing(p2));
  m->confidence.push_back(confidence);
}

TEST(RelativePoseSamplingTest, GridTakesBestSpreadCellsAndMostConfidentMatch) {
  TwoViewCorrespondences m;
  m.width1 = m.width2 = kWidth;
  m.height1 = m.height2 = kHeight;
  // Cell 0 scores 5, its neighbour 1 scores 4 (too close at distance 2), then cells far apart.
  const std::vector<std::pair<int, int>> cell_scores = {{0, 5},  {1, 4},  {4, 3},  {7, 3},
                                                        {24, 3}, {28, 2}, {47, 2}, {44, 1}};
  for (const auto& [cell, score] : cell_scores) {
    for (int i = 0; i < score; ++i) {
      AddMatch(&m, CellCenter(cell, i), CellCenter(cell, -i), 1.0 + i);
    }
  }
  // The most confident match of all is cross-cell and must not be chosen.
  AddMatch(&m, CellCenter(2), CellCenter(40), 0.0);
  const std::vector<int> scores = GridCorrespondenceScores(m, 8, 6);
  EXPECT_EQ(scores[0], 5);
  EXPECT_EQ(scores[2], 0);
  const std::vector<int> six = SelectGridCorrespondences(m, 8, 6, 6, 2);
  ASSERT_EQ(six.size(), 6u);
  const ImageGrid grid{8, 6, kWidth, kHeight};
  std::set<int> cells;
  for (int k : six) {
    cells.insert(grid.CellIndex(m.pixels1[k]));
    EXPECT_EQ(m.confidence[k], 1.0) << "not the cell's most confident match";
  }
  EXPECT_EQ(cells, (std::set<int>{0, 4, 7, 24, 28, 47}));
}

TEST(RelativePoseSamplingTest, GridFillsWhenFewCellsScore) {
  TwoViewCorrespondences m;
  m.width1 = m.width2 = kWidth;
  m.height1 = m.height2 = kHeight;
  AddMatch(&m, CellCenter(0), CellCenter(0), 1.0);
  AddMatch(&m, CellCenter(20), CellCenter(20), 1.0);
  // Cross-cell matches: image-1 cell 9 -> image-2 cell 10 is the most populated assignment.
  for (int i = 0; i < 3; ++i) AddMatch(&m, CellCenter(9, i), CellCenter(10, i), 2.0 + i);
  AddMatch(&m, CellCenter(30), CellCenter(31), 0.5);
  AddMatch(&m, CellCenter(40), CellCenter(33), 0.7);
  AddMatch(&m, CellCenter(41), CellCenter(34), 0.9);
  const std::vector<int> six = SelectGridCorrespondences(m, 8, 6, 6, 2);
  ASSERT_EQ(six.size(), 6u);
  EXPECT_EQ(std::set<int>(six.begin(), six.end()), (std::set<int>{0, 1, 2, 5, 6, 7}));
  EXPECT_EQ(std::set<int>(six.begin(), six.end()).size(), 6u);
}

TEST(RelativePoseSamplingTest, RandomAndRoi) {
  const Motion motion = Motions()[2];
  const SyntheticPair pair = MakePair(motion.R, motion.center2, 100, 0, 8);
  const std::vector<int> a = SelectRandomCorrespondences(pair.matches, 6, 42);
  EXPECT_EQ(a, SelectRandomCorrespondences(pair.matches, 6, 42));
  EXPECT_NE(a, SelectRandomCorrespondences(pair.matches, 6, 43));
  EXPECT_EQ(std::set<int>(a.begin(), a.end()).size(), 6u);
  const std::vector<int> roi = SelectRoiCorrespondences(pair.matches, 8, 6, 6);
  ASSERT_EQ(roi.size(), 6u);
  // All six within one block of at most 2 x 2 cells (100 matches over 48 cells).
  const ImageGrid grid{8, 6, kWidth, kHeight};
  int min_col = 8, max_col = -1, min_row = 6, max_row = -1;
  for (int k : roi) {
    const int c = grid.CellIndex(pair.matches.pixels1[k]);
    min_col = std::min(min_col, c % 8), max_col = std::max(max_col, c % 8);
    min_row = std::min(min_row, c / 8), max_row = std::max(max_row, c / 8);
  }
  EXPECT_LE(max_col - min_col, 1);
  EXPECT_LE(max_row - min_row, 1);
}

}  // namespace
}  // namespace ramap

namespace ramap {
namespace {

// The paper's ablation on synthetic pairs (not run by default: it prints a table; run with
// --gtest_also_run_disabled_tests --gtest_filter='*RelativePoseAblation*').
TEST(RelativePoseTest, DISABLED_RelativePoseAblation) {
  const std::vector<CorrespondenceSampler> samplers = {
      CorrespondenceSampler::kGrid, CorrespondenceSampler::kRandom, CorrespondenceSampler::kRoi,
      CorrespondenceSampler::kRansac5};
  for (const Motion& motion : Motions()) {
    for (CorrespondenceSampler sampler : samplers) {
      std::vector<double> rotation_errors, translation_errors;
      int failures = 0;
      const auto start = std::chrono::steady_clock::now();
      constexpr int kTrials = 50;
      for (int trial = 0; trial < kTrials; ++trial) {
        SyntheticPair pair = MakePair(motion.R, motion.center2, 300, 1.0, 100 + trial);
        // 10% wrong partners, rated like the rest (confidence uninformative).
        for (size_t k = 0; k < pair.matches.size(); k += 10) {
          const size_t other = (k * 7 + 13) % pair.matches.size();
          pair.matches.bearings2[k] = pair.matches.bearings2[other];
          pair.matches.pixels2[k] = pair.matches.pixels2[other];
        }
        RelativePoseOptions options;
        options.sampler = sampler;
        options.seed = trial;
        const RelativePoseEstimate estimate = EstimateRelativePose(pair.matches, options);
        if (!estimate.success) {
          if (std::getenv("RAMAP_ABLATION_VERBOSE")) std::printf("  %s\n", estimate.reason.c_str());
          ++failures;
          continue;
        }
        rotation_errors.push_back(RotationErrorDeg(estimate, pair.R));
        translation_errors.push_back(TranslationErrorDeg(estimate, pair.t));
      }
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count() /
          kTrials;
      std::sort(rotation_errors.begin(), rotation_errors.end());
      std::sort(translation_errors.begin(), translation_errors.end());
      auto median = [](const std::vector<double>& v) { return v.empty() ? -1 : v[v.size() / 2]; };
      auto worst = [](const std::vector<double>& v) { return v.empty() ? -1 : v.back(); };
      std::printf(
          "%-9s %-8s rejected %2d/%d  rot median %.4f max %.4f deg  t median %.3f max %.3f deg  "
          "%.2f ms\n",
          motion.name, CorrespondenceSamplerName(sampler).c_str(), failures, kTrials,
          median(rotation_errors), worst(rotation_errors), median(translation_errors),
          worst(translation_errors), ms);
    }
  }
}

}  // namespace
}  // namespace ramap
