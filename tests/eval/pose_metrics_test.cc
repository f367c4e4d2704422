#include "ramap/eval/pose_metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>

#include "eval/eval_test_scenes.h"
#include "ramap/util/error.h"

namespace ramap::test {
namespace {

using PoseMap = std::map<std::string, Rigid3d>;

PoseMap NoisyCopy(const PoseMap& poses, double centre_sigma, double angle_sigma_deg,
                  std::mt19937_64& rng) {
  PoseMap out;
  std::normal_distribution<double> angle(0.0, angle_sigma_deg);
  for (const auto& [name, pose] : poses) {
    const Eigen::Vector3d centre = CameraCenter(pose) + RandomVector(rng, centre_sigma);
    Rigid3d turned = RotatedInPlace(pose, RandomVector(rng, 1.0), angle(rng));
    out[name] = Rigid3d(turned.rotation, -(turned.rotation * centre));
  }
  return out;
}

TEST(EvalPoseMetrics, ExactSimilarityCopyScoresPerfectly) {
  std::mt19937_64 rng(10);
  const PoseMap gt = RandomCameras(10, rng);
  const Sim3d est_from_gt = RandomSim3(rng);
  const PoseEvaluation e = EvaluatePoses(Transformed(gt, est_from_gt), gt, Names(gt));
  EXPECT_EQ(e.num_images, 10);
  EXPECT_EQ(e.num_registered, 10);
  EXPECT_EQ(e.num_evaluated, 10);
  ASSERT_EQ(e.alignment_status, AlignmentStatus::kSuccess);
  EXPECT_NEAR(e.gt_from_estimate.scale, 1.0 / est_from_gt.scale, 1e-9 / est_from_gt.scale);
  EXPECT_NEAR(e.gt_from_estimate.rotation.angularDistance(est_from_gt.rotation.conjugate()), 0.0,
              1e-9);
  EXPECT_LT(e.ate_rmse, 1e-9 * e.gt_extent);
  EXPECT_LT(e.ate_max, 1e-9 * e.gt_extent);
  EXPECT_LT(e.rotation_error_max_deg, 1e-7);
  EXPECT_EQ(e.num_pairs, 45);
  EXPECT_EQ(e.num_failed_pairs, 0);
  EXPECT_LT(e.relative_rotation_error_median_deg, 1e-7);
  ASSERT_EQ(e.auc.size(), 4u);
  for (double auc : e.auc) EXPECT_NEAR(auc, 1.0, 1e-9);
}

TEST(EvalPoseMetrics, OneImageRotatedByTwoDegrees) {
  std::mt19937_64 rng(11);
  const PoseMap gt = RandomCameras(10, rng);
  PoseMap perturbed = gt;
  perturbed["img_03"] = RotatedInPlace(gt.at("img_03"), Eigen::Vector3d(0.3, -1.0, 0.4), 2.0);
  const PoseMap est = Transformed(perturbed, RandomSim3(rng));
  const PoseEvaluation e = EvaluatePoses(est, gt, Names(gt));
  ASSERT_EQ(e.alignment_status, AlignmentStatus::kSuccess);
  // Centres are untouched, so the alignment is exact and only img_03's orientation is off.
  EXPECT_LT(e.ate_max, 1e-9 * e.gt_extent);
  for (const ImageEvaluation& image : e.images) {
    EXPECT_NEAR(image.rotation_error_deg, image.name == "img_03" ? 2.0 : 0.0, 1e-9) << image.name;
  }
  EXPECT_NEAR(e.rotation_error_max_deg, 2.0, 1e-9);
  EXPECT_NEAR(e.rotation_error_mean_deg, 0.2, 1e-9);

  // Every pair with img_03 is off by exactly 2 degrees (its rotation; the translation direction is
  // off by at most 2), every other pair by nothing.
  const std::vector<std::string> names = Names(gt);
  for (size_t a = 0; a < names.size(); ++a) {
    for (size_t b = a + 1; b < names.size(); ++b) {
      const PairPoseError p =
          RelativePoseError(est.at(names[a]), est.at(names[b]), gt.at(names[a]), gt.at(names[b]));
      const bool involved = names[a] == "img_03" || names[b] == "img_03";
      EXPECT_NEAR(p.rotation_deg, involved ? 2.0 : 0.0, 1e-9);
      EXPECT_NEAR(p.error_deg(), involved ? 2.0 : 0.0, 1e-9);
      EXPECT_LE(p.translation_deg, 2.0 + 1e-9);
    }
  }
  // 45 pairs: 36 at 0 deg, 9 at 2 deg. Benchmark curve: (0, 36/45) to (2, 37/45), then recall 1.
  // T=1: recall 36/45 throughout -> 0.8. T>=2: area 2*(36+37)/90 + (T-2), divided by T.
  EXPECT_NEAR(e.auc[0], 0.8, 1e-9);
  EXPECT_NEAR(e.auc[1], (73.0 / 45.0 + 1.0) / 3.0, 1e-9);
  EXPECT_NEAR(e.auc[2], (73.0 / 45.0 + 3.0) / 5.0, 1e-9);
  EXPECT_NEAR(e.auc[3], (73.0 / 45.0 + 8.0) / 10.0, 1e-9);
  EXPECT_LT(e.relative_rotation_error_median_deg, 1e-9);
}

TEST(EvalPoseMetrics, UnregisteredImagesAreFailures) {
  std::mt19937_64 rng(12);
  const PoseMap gt = RandomCameras(10, rng);
  PoseMap est = Transformed(gt, RandomSim3(rng));
  est.erase("img_02");
  est.erase("img_07");
  const PoseEvaluation e = EvaluatePoses(est, gt, Names(gt));
  EXPECT_EQ(e.num_registered, 8);
  EXPECT_EQ(e.num_evaluated, 8);
  EXPECT_EQ(e.num_pairs, 45);
  EXPECT_EQ(e.num_failed_pairs, 45 - 28);
  for (double auc : e.auc) EXPECT_NEAR(auc, 28.0 / 45.0, 1e-9);
  EXPECT_TRUE(std::isinf(e.pair_error_median_deg) || e.pair_error_median_deg < 1e-9);
  EXPECT_FALSE(e.images[2].registered);
  EXPECT_EQ(e.images[2].position_error, -1.0);

  // With noise too: AUC over the 10 inputs is the AUC over the 8 registered ones times 28/45.
  const PoseMap noisy = NoisyCopy(gt, 0.05, 1.5, rng);
  PoseMap noisy_partial = noisy;
  noisy_partial.erase("img_02");
  noisy_partial.erase("img_07");
  std::vector<std::string> registered_names;
  for (const auto& [name, pose] : noisy_partial) registered_names.push_back(name);
  const PoseEvaluation all = EvaluatePoses(noisy_partial, gt, Names(gt));
  const PoseEvaluation only = EvaluatePoses(noisy_partial, gt, registered_names);
  ASSERT_EQ(only.num_failed_pairs, 0);
  for (size_t k = 0; k < all.auc.size(); ++k) {
    EXPECT_GT(only.auc[k], 0.0);
    EXPECT_NEAR(all.auc[k], only.auc[k] * 28.0 / 45.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(all.ate_rmse, only.ate_rmse);  // the same 8 images are aligned
}

TEST(EvalPoseMetrics, RobustAlignmentIgnoresGrossOutlierCamera) {
  std::mt19937_64 rng(13);
  const PoseMap gt = RandomCameras(10, rng);
  PoseMap moved = gt;
  const Eigen::Vector3d shift(60.0, -80.0, 0.0);  // 100 units
  const Rigid3d& pose = gt.at("img_04");
  moved["img_04"] = Rigid3d(pose.rotation, -(pose.rotation * (CameraCenter(pose) + shift)));
  const PoseMap est = Transformed(moved, RandomSim3(rng));

  PoseEvaluationOptions options;
  const PoseEvaluation plain = EvaluatePoses(est, gt, Names(gt), options);
  EXPECT_GT(plain.ate_median, 1.0);  // least squares spreads the outlier over everyone

  options.alignment.robust = true;
  options.alignment.robust_max_error = 0.05;
  const PoseEvaluation robust = EvaluatePoses(est, gt, Names(gt), options);
  ASSERT_EQ(robust.alignment_status, AlignmentStatus::kSuccess);
  EXPECT_EQ(robust.num_alignment_inliers, 9);
  for (const ImageEvaluation& image : robust.images) {
    EXPECT_EQ(image.alignment_inlier, image.name != "img_04");
    EXPECT_NEAR(image.position_error, image.name == "img_04" ? 100.0 : 0.0, 1e-8) << image.name;
    EXPECT_NEAR(image.rotation_error_deg, 0.0, 1e-7);
  }
  EXPECT_NEAR(robust.ate_max, 100.0, 1e-8);
  EXPECT_NEAR(robust.ate_rmse, 100.0 / std::sqrt(10.0), 1e-8);
}

// The rhombus (+-2, 0, 0), (0, +-1, 0) aligned to the square (+-1, 0, 0), (0, +-1, 0): by symmetry
// R = I and t = 0, and the least-squares scale is sum(d . s) / sum(|s|^2) = 6 / 10. Residuals are
// |1.2 - 1| = 0.2 (twice) and |0.6 - 1| = 0.4 (twice): RMSE sqrt(0.1), median 0.3, max 0.4.
TEST(EvalPoseMetrics, HandComputedAteAndSceneSize) {
  auto at = [](double x, double y) {
    return Rigid3d(Eigen::Quaterniond::Identity(), -Eigen::Vector3d(x, y, 0));
  };
  const PoseMap gt = {{"a", at(1, 0)}, {"b", at(0, 1)}, {"c", at(-1, 0)}, {"d", at(0, -1)}};
  const PoseMap rhombus = {{"a", at(2, 0)}, {"b", at(0, 1)}, {"c", at(-2, 0)}, {"d", at(0, -1)}};
  std::mt19937_64 rng(14);
  const PoseEvaluation e =
      EvaluatePoses(Transformed(rhombus, RandomSim3(rng)), gt, {"a", "b", "c", "d"});
  ASSERT_EQ(e.alignment_status, AlignmentStatus::kSuccess);
  EXPECT_NEAR(e.ate_rmse, std::sqrt(0.1), 1e-12);
  EXPECT_NEAR(e.ate_median, 0.3, 1e-12);
  EXPECT_NEAR(e.ate_mean, 0.3, 1e-12);
  EXPECT_NEAR(e.ate_max, 0.4, 1e-12);
  EXPECT_LT(e.rotation_error_max_deg, 1e-7);
  // Path a-b-c-d: three sides of length sqrt(2); extent: every corner is 1 from the centroid.
  EXPECT_NEAR(e.gt_path_length, 3.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(e.gt_extent, 1.0, 1e-12);
  EXPECT_NEAR(e.ate_rmse_over_path_length, std::sqrt(0.1) / (3.0 * std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(e.ate_rmse_over_extent, std::sqrt(0.1), 1e-12);
}

// Horn, "Closed-form solution of absolute orientation using unit quaternions", JOSA A 4(4), 1987:
// the rotation is the top eigenvector of a 4x4 matrix built from the cross-covariance, a route
// independent of the SVD that Eigen::umeyama takes. Scale is the least-squares one.
Sim3d HornAlignment(const std::vector<Eigen::Vector3d>& src,
                    const std::vector<Eigen::Vector3d>& dst) {
  Eigen::Vector3d src_mean = Eigen::Vector3d::Zero(), dst_mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < src.size(); ++i) {
    src_mean += src[i];
    dst_mean += dst[i];
  }
  src_mean /= src.size();
  dst_mean /= dst.size();
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();  // s(a, b) = sum src'_a dst'_b
  for (size_t i = 0; i < src.size(); ++i) {
    s += (src[i] - src_mean) * (dst[i] - dst_mean).transpose();
  }
  const double sxx = s(0, 0), sxy = s(0, 1), sxz = s(0, 2), syx = s(1, 0), syy = s(1, 1),
               syz = s(1, 2), szx = s(2, 0), szy = s(2, 1), szz = s(2, 2);
  Eigen::Matrix4d n;
  n << sxx + syy + szz, syz - szy, szx - sxz, sxy - syx,  //
      syz - szy, sxx - syy - szz, sxy + syx, szx + sxz,   //
      szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy,  //
      sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(n);
  const Eigen::Vector4d q = eig.eigenvectors().col(3);  // largest eigenvalue last
  Sim3d sim;
  sim.rotation = Eigen::Quaterniond(q(0), q(1), q(2), q(3)).normalized();
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < src.size(); ++i) {
    num += (dst[i] - dst_mean).dot(sim.rotation * (src[i] - src_mean));
    den += (src[i] - src_mean).squaredNorm();
  }
  sim.scale = num / den;
  sim.translation = dst_mean - sim.scale * (sim.rotation * src_mean);
  return sim;
}

TEST(EvalPoseMetrics, AteAgreesWithIndependentHornAlignment) {
  std::mt19937_64 rng(15);
  for (int trial = 0; trial < 5; ++trial) {
    const PoseMap gt = RandomCameras(7 + 3 * trial, rng);
    const PoseMap est = Transformed(NoisyCopy(gt, 0.2, 3.0, rng), RandomSim3(rng));
    std::vector<Eigen::Vector3d> src, dst;
    for (const auto& [name, pose] : gt) {
      src.push_back(CameraCenter(est.at(name)));
      dst.push_back(CameraCenter(pose));
    }
    const Sim3d horn = HornAlignment(src, dst);
    double sum_sq = 0.0;
    double sum_rotation_deg = 0.0;
    for (const auto& [name, pose] : gt) {
      sum_sq += (horn * CameraCenter(est.at(name)) - CameraCenter(pose)).squaredNorm();
      // R_aligned = R_est R_horn^T; its error against R_gt, written out with matrices.
      const Eigen::Matrix3d r_aligned =
          est.at(name).rotation.toRotationMatrix() * horn.rotation.toRotationMatrix().transpose();
      const Eigen::Matrix3d d = pose.rotation.toRotationMatrix().transpose() * r_aligned;
      sum_rotation_deg += std::acos(std::clamp((d.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
    }
    const double horn_rmse = std::sqrt(sum_sq / gt.size());

    const PoseEvaluation e = EvaluatePoses(est, gt, Names(gt));
    ASSERT_EQ(e.alignment_status, AlignmentStatus::kSuccess);
    EXPECT_GT(horn_rmse, 0.05);  // a real, noisy case
    EXPECT_NEAR(e.ate_rmse, horn_rmse, 1e-9 * horn_rmse);
    EXPECT_NEAR(e.gt_from_estimate.scale, horn.scale, 1e-9 * horn.scale);
    EXPECT_NEAR(e.rotation_error_mean_deg, sum_rotation_deg / gt.size(), 1e-6);
  }
}

TEST(EvalPoseMetrics, RigidAlignmentDoesNotAbsorbScale) {
  std::mt19937_64 rng(16);
  const PoseMap gt = RandomCameras(8, rng);
  const PoseMap est = Transformed(gt, Sim3d(2.0, RandomRotation(rng), RandomVector(rng, 3.0)));
  PoseEvaluationOptions options;
  EXPECT_LT(EvaluatePoses(est, gt, Names(gt), options).ate_rmse, 1e-9);
  options.alignment.estimate_scale = false;
  const PoseEvaluation rigid = EvaluatePoses(est, gt, Names(gt), options);
  EXPECT_GT(rigid.ate_rmse, 0.5);
  EXPECT_EQ(rigid.gt_from_estimate.scale, 1.0);
  // Relative errors need no alignment and are scale-free.
  for (double auc : rigid.auc) EXPECT_NEAR(auc, 1.0, 1e-9);
}

TEST(EvalPoseMetrics, DegenerateGroundTruthStillScoresRelativePoses) {
  PoseMap gt;
  for (int i = 0; i < 5; ++i) {
    gt["f" + std::to_string(i)] =
        Rigid3d(Eigen::Quaterniond::Identity(), -Eigen::Vector3d(0, 0, 1.5 * i));  // a line
  }
  std::mt19937_64 rng(17);
  const PoseEvaluation e = EvaluatePoses(Transformed(gt, RandomSim3(rng)), gt, Names(gt));
  EXPECT_EQ(e.alignment_status, AlignmentStatus::kCollinearPoints);
  EXPECT_TRUE(std::isnan(e.ate_rmse));
  EXPECT_TRUE(std::isnan(e.rotation_error_median_deg));
  EXPECT_NEAR(e.gt_path_length, 6.0, 1e-12);
  for (double auc : e.auc) EXPECT_NEAR(auc, 1.0, 1e-9);
  const nlohmann::json j = PoseEvaluationToJson(e);
  EXPECT_TRUE(j["ate"]["rmse"].is_null());
  EXPECT_EQ(j["alignment"]["status"], "collinear_points");
}

TEST(EvalPoseMetrics, InputBookkeeping) {
  std::mt19937_64 rng(18);
  const PoseMap gt = RandomCameras(6, rng);
  PoseMap est = Transformed(gt, RandomSim3(rng));
  est["not_an_input"] = Rigid3d();
  std::vector<std::string> names = Names(gt);
  names.push_back("no_ground_truth");
  PoseEvaluationOptions options;
  options.ordered_pairs = true;
  const PoseEvaluation e = EvaluatePoses(est, gt, names, options);
  EXPECT_EQ(e.num_images, 7);
  EXPECT_EQ(e.num_registered, 6);
  EXPECT_EQ(e.num_with_ground_truth, 6);
  EXPECT_EQ(e.num_estimated_not_in_input, 1);
  EXPECT_EQ(e.num_pairs, 30);  // 15 unordered pairs, both orders

  names.push_back(names.front());
  EXPECT_THROW(EvaluatePoses(est, gt, names), InputError);
  options.auc_thresholds_deg = {};
  EXPECT_THROW(EvaluatePoses(est, gt, Names(gt), options), InputError);
}

TEST(EvalPoseMetrics, JsonAndTable) {
  std::mt19937_64 rng(19);
  const PoseMap gt = RandomCameras(6, rng);
  PoseMap est = NoisyCopy(gt, 0.1, 1.0, rng);
  est.erase("img_01");
  const PoseEvaluation e = EvaluatePoses(est, gt, Names(gt));
  const nlohmann::json j = PoseEvaluationToJson(e);
  EXPECT_EQ(j["num_images"], 6);
  EXPECT_EQ(j["num_registered"], 5);
  EXPECT_DOUBLE_EQ(j["ate"]["rmse"].get<double>(), e.ate_rmse);
  EXPECT_DOUBLE_EQ(j["relative"]["auc_by_threshold_deg"]["5"].get<double>(), e.auc[2]);
  EXPECT_EQ(j["relative"]["auc_thresholds_deg"], nlohmann::json({1.0, 3.0, 5.0, 10.0}));
  EXPECT_DOUBLE_EQ(j["relative"]["auc"][2].get<double>(), e.auc[2]);
  EXPECT_EQ(j["images"].size(), 6u);
  EXPECT_TRUE(j["images"][1]["position_error"].is_null());
  const std::string table = FormatPoseEvaluation(e);
  EXPECT_NE(table.find("5 / 6"), std::string::npos) << table;
  EXPECT_NE(table.find("AUC"), std::string::npos);
}

// The report plots the recall curve whose area the AUC is: integrated, it gives the AUC back (to
// its 0.1-degree sampling), and it ends at the share of pairs within the largest threshold.
TEST(EvalPoseMetrics, RecallCurveIntegratesToTheAuc) {
  std::mt19937_64 rng(21);
  const PoseMap gt = RandomCameras(30, rng);
  PoseMap est = NoisyCopy(gt, 0.02, 2.0, rng);
  est.erase("img_07");
  const PoseEvaluation e = EvaluatePoses(est, gt, Names(gt));
  ASSERT_EQ(e.recall_curve.size(), 101u);
  EXPECT_DOUBLE_EQ(e.recall_curve_thresholds_deg.back(), 10.0);
  EXPECT_DOUBLE_EQ(e.recall_curve.front(), 0.0);
  EXPECT_TRUE(std::is_sorted(e.recall_curve.begin(), e.recall_curve.end()));
  EXPECT_LE(e.recall_curve.back(), 1.0 - static_cast<double>(e.num_failed_pairs) / e.num_pairs);
  double area = 0.0;
  for (size_t k = 1; k < e.recall_curve.size(); ++k) {
    area += 0.5 * (e.recall_curve[k] + e.recall_curve[k - 1]) *
            (e.recall_curve_thresholds_deg[k] - e.recall_curve_thresholds_deg[k - 1]);
  }
  EXPECT_NEAR(area / 10.0, e.auc.back(), 0.01) << "AUC@10 from the curve and from the errors";
}

}  // namespace
}  // namespace ramap::test
