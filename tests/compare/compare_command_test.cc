// `ramap compare` on a synthetic scene: the report's numbers are those `ramap evaluate` gives for
// the same models, and they agree with `colmap model_comparer`'s independent alignment.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "ramap/eval/pose_metrics.h"
#include "ramap/geometry/alignment.h"
#include "ramap/io/colmap_model.h"
#include "test_support.h"

namespace ramap::test {
namespace {

// The "Median:" value of the section of `output` that starts with `heading`.
double MedianAfter(const std::string& output, const std::string& heading) {
  const size_t at = output.find(heading);
  EXPECT_NE(at, std::string::npos) << heading << " not in:\n" << output;
  std::smatch match;
  const std::string rest = at == std::string::npos ? "" : output.substr(at);
  EXPECT_TRUE(std::regex_search(rest, match, std::regex("Median:\\s*([0-9.eE+-]+)"))) << rest;
  return match.empty() ? NAN : std::stod(match[1]);
}

// The 4 x 4 matrix after "Computed alignment transform:" as a Sim3d.
Sim3d AlignmentTransformIn(const std::string& output) {
  const size_t at = output.find("Computed alignment transform:");
  EXPECT_NE(at, std::string::npos) << output;
  std::istringstream in(output.substr(at + std::strlen("Computed alignment transform:")));
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) in >> m(r, c);
  }
  const Eigen::Matrix3d sR = m.topLeftCorner<3, 3>();
  const double scale = std::cbrt(sR.determinant());
  return Sim3d(scale, Eigen::Quaterniond(sR / scale), m.topRightCorner<3, 1>());
}

// COLMAP's median: the mean of the two middle values of an even count.
double ColmapMedian(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const nlohmann::json& RunNamed(const nlohmann::json& report, const std::string& name) {
  for (const nlohmann::json& run : report["runs"]) {
    if (run["name"] == name) return run;
  }
  ADD_FAILURE() << "no run " << name;
  static const nlohmann::json none;
  return none;
}

// The database of a synthetic orbit in dir/scene, made by `ramap synthesize` with `options`; empty
// (and a test failure) when that fails.
std::string SynthesizeCircle(const TempDir& dir, const std::string& options) {
  const CommandResult result = RunCommand("'" + RamapBinary() + "' synthesize --output_path '" +
                                          (dir / "scene") + "' --Synthetic.path circle " + options);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return result.exit_code == 0 ? dir / "scene/database.db" : "";
}

TEST(CompareCommand, ReportAgreesWithEvaluateAndColmapModelComparer) {
  RAMAP_REQUIRE_COLMAP();
  TempDir dir;
  const std::string ramap = "'" + RamapBinary() + "' ";
  const std::string db = SynthesizeCircle(dir,
                                          "--Synthetic.num_images 16 --Synthetic.num_points 1500 "
                                          "--Synthetic.pixel_noise 0.5 --Synthetic.seed 2");
  ASSERT_FALSE(db.empty());

  // Without ground truth: the ramap models are scored against COLMAP's.
  const CommandResult compare =
      RunCommand(ramap + "compare --database_path '" + db + "' --output_path '" + (dir / "cmp") +
                 "' --Compare.png_figures 1");
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  const nlohmann::json report = test::ReadJsonFile(dir / "cmp/report.json");
  for (const std::string figure : {"trajectories.png", "rotation_error_cdf.png",
                                   "position_error_cdf.png", "stage_times.png"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / ("cmp/" + figure))) << figure;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "cmp/report.md"));
  ASSERT_EQ(report["runs"].size(), 3u);
  // report.html draws each run's model: as many cameras as the run registered.
  const nlohmann::json page = test::ReportPageData(dir / "cmp/report.html");
  ASSERT_EQ(page["models"].size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(page["models"][k]["name"], report["runs"][k]["name"]);
    EXPECT_EQ(page["models"][k]["images"]["name"].size(),
              report["runs"][k]["num_registered"].get<size_t>());
  }
  EXPECT_EQ(page["recall_curves"].size(), 2u) << "COLMAP is the reference: two scored runs";
  const nlohmann::json& colmap_run = RunNamed(report, "COLMAP");
  ASSERT_TRUE(colmap_run["succeeded"].get<bool>());
  EXPECT_TRUE(colmap_run["evaluation"].is_null());  // it is the reference
  for (const std::string name : {"ramap", "ramap+BA"}) {
    const nlohmann::json& run = RunNamed(report, name);
    ASSERT_TRUE(run["succeeded"].get<bool>()) << name;
    EXPECT_EQ(run["num_registered"], 16);
    EXPECT_NEAR(run["speedup_over_colmap"].get<double>(),
                colmap_run["seconds"].get<double>() / run["seconds"].get<double>(), 1e-9);
    const std::string model = run["model_path"];
    // `ramap evaluate` on the same two models gives the same numbers.
    const CommandResult evaluate =
        RunCommand(ramap + "evaluate --model_path '" + model + "' --ground_truth '" +
                   colmap_run["model_path"].get<std::string>() + "' --ground_truth_format colmap" +
                   " --database_path '" + db + "' --output_path '" + (dir / "eval.json") + "'");
    ASSERT_EQ(evaluate.exit_code, 0) << evaluate.output;
    const nlohmann::json evaluation = test::ReadJsonFile(dir / "eval.json");
    const nlohmann::json& reported = run["evaluation"];
    // (Both read the models from disk; summation order may differ in the last bits.)
    auto expect_same = [&](const nlohmann::json& a, const nlohmann::json& b) {
      EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-9 * std::abs(b.get<double>()) + 1e-15)
          << name;
    };
    expect_same(reported["ate"]["rmse"], evaluation["ate"]["rmse"]);
    expect_same(reported["ate"]["median"], evaluation["ate"]["median"]);
    expect_same(reported["rotation_error_deg"]["median"],
                evaluation["rotation_error_deg"]["median"]);
    for (size_t k = 0; k < 4; ++k) {
      expect_same(reported["relative"]["auc"][k], evaluation["relative"]["auc"][k]);
    }

    // COLMAP aligns by its own (reprojection-based) method. Under the transform it prints, our
    // error computation reproduces its statistics; and our least-squares alignment of the centres
    // leaves no larger an RMSE than its transform does.
    const std::string reference = colmap_run["model_path"];
    const CommandResult comparer = RunCommand("colmap model_comparer --input_path1 '" + model +
                                              "' --input_path2 '" + reference + "'");
    ASSERT_EQ(comparer.exit_code, 0) << comparer.output;
    const Sim3d colmap_transform = AlignmentTransformIn(comparer.output);
    const std::map<std::string, Rigid3d> ours = PosesByName(ReadColmapModel(model));
    const std::map<std::string, Rigid3d> theirs = PosesByName(ReadColmapModel(reference));
    std::vector<double> center_errors, rotation_errors;
    double squared = 0;
    // Its transform maps model 2 into model 1, whose units its distances are in.
    for (const auto& [image, pose] : ours) {
      const Rigid3d moved = TransformPose(colmap_transform, theirs.at(image));
      center_errors.push_back((moved.Inverse().translation - pose.Inverse().translation).norm());
      squared += center_errors.back() * center_errors.back();
      rotation_errors.push_back(RotationAngleDeg(moved.rotation, pose.rotation));
    }
    const double colmap_center = MedianAfter(comparer.output, "Projection center distance");
    const double colmap_rotation = MedianAfter(comparer.output, "Rotation angular errors");
    std::printf(
        "%s: model_comparer medians: centre %.6g rotation %.6g deg; ours under its "
        "transform %.6g, %.6g; our ATE median %.6g\n",
        name.c_str(), colmap_center, colmap_rotation, ColmapMedian(center_errors),
        ColmapMedian(rotation_errors), reported["ate"]["median"].get<double>());
    // It prints its transform to 6 digits: ~1e-6 of the scene in the centres, ~1e-4 deg.
    EXPECT_NEAR(ColmapMedian(center_errors), colmap_center, 1e-2 * colmap_center);
    EXPECT_NEAR(ColmapMedian(rotation_errors), colmap_rotation, 2e-4);
    // In the reference's units (model 2's) that RMSE is divided by the transform's scale.
    EXPECT_LE(reported["ate"]["rmse"].get<double>(),
              std::sqrt(squared / center_errors.size()) / colmap_transform.scale * (1 + 1e-9));
  }

  // With ground truth every run is scored against it, COLMAP's too.
  const CommandResult with_gt = RunCommand(
      ramap + "compare --database_path '" + db + "' --output_path '" + (dir / "cmp_gt") +
      "' --ground_truth '" + (dir / "scene/ground_truth") + "' --ground_truth_format colmap");
  ASSERT_EQ(with_gt.exit_code, 0) << with_gt.output;
  const nlohmann::json gt_report = test::ReadJsonFile(dir / "cmp_gt/report.json");
  for (const nlohmann::json& run : gt_report["runs"]) {
    ASSERT_FALSE(run["evaluation"].is_null()) << run["name"];
    EXPECT_LT(run["evaluation"]["ate"]["rmse_over_extent"].get<double>(), 0.01) << run["name"];
  }
}

// COLMAP 3.8 reads no 4.x database (and would stamp its version on one): it maps a 3.8 copy, and
// the user's database is left as it was.
TEST(CompareCommand, ColmapMapsA38CopyOfA4xDatabase) {
  RAMAP_REQUIRE_COLMAP();
  TempDir dir;
  const std::string ramap = "'" + RamapBinary() + "' ";
  const std::string db = SynthesizeCircle(dir,
                                          "--Synthetic.num_images 8 --Synthetic.num_points 800 "
                                          "--Synthetic.seed 5 --Database.generation 4");
  ASSERT_FALSE(db.empty());
  std::ifstream before_file(db, std::ios::binary);
  const std::string before((std::istreambuf_iterator<char>(before_file)),
                           std::istreambuf_iterator<char>());
  const CommandResult compare = RunCommand(ramap + "compare --database_path '" + db +
                                           "' --output_path '" + (dir / "cmp") + "'");
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  const nlohmann::json report = test::ReadJsonFile(dir / "cmp/report.json");
  EXPECT_TRUE(RunNamed(report, "COLMAP")["succeeded"].get<bool>()) << compare.output;
  EXPECT_EQ(RunNamed(report, "COLMAP")["num_registered"], 8);
  EXPECT_FALSE(std::filesystem::exists(dir / "cmp/colmap.database.db"));
  std::ifstream after_file(db, std::ios::binary);
  const std::string after((std::istreambuf_iterator<char>(after_file)),
                          std::istreambuf_iterator<char>());
  EXPECT_TRUE(before == after) << "the compared database changed";
}

TEST(CompareCommand, GroundTruthNeedsItsFormat) {
  TempDir dir;
  const CommandResult result =
      RunCommand("'" + RamapBinary() + "' compare --database_path x.db" + " --output_path '" +
                 (dir / "out") + "' --ground_truth gt.txt");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("--ground_truth_format"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace ramap::test
