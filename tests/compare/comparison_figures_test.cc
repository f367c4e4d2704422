// The comparison's figures: each succeeded run's stage bar with the time its stages do not cover,
// and the figure files drawn and listed, the error figures only when some run was evaluated.
#include "ramap/compare/comparison_figures.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

MapperRun MakeRun(const std::string& name, bool succeeded, double seconds,
                  std::vector<std::pair<std::string, double>> stages) {
  MapperRun run;
  run.name = name;
  run.succeeded = succeeded;
  run.seconds = seconds;
  run.stage_seconds = std::move(stages);
  return run;
}

TEST(ComparisonFigures, StageBarsAddTheTimeTheStagesDoNotCover) {
  const std::vector<StageBar> bars = StageBars({
      MakeRun("COLMAP", true, 10.0, {}),
      MakeRun("GLOMAP", false, 3.0, {{"rotation averaging", 1.0}}),
      MakeRun("ramap", true, 4.0, {{"relative poses", 1.0}, {"rotation averaging", 2.5}}),
      MakeRun("ramap+BA", true, 2.0, {{"bundle adjustment", 3.0}}),
  });
  ASSERT_EQ(bars.size(), 3u);  // the failed run has none
  EXPECT_EQ(bars[0].label, "COLMAP");
  EXPECT_EQ(bars[0].stages, (std::vector<std::pair<std::string, double>>{{"whole mapper", 10.0}}));
  EXPECT_EQ(bars[1].label, "ramap");
  EXPECT_EQ(bars[1].stages,
            (std::vector<std::pair<std::string, double>>{
                {"relative poses", 1.0}, {"rotation averaging", 2.5}, {"input / output", 0.5}}));
  // Stages summing to more than the process (a clock's rounding): no negative rest.
  EXPECT_EQ(bars[2].stages.back(), (std::pair<std::string, double>{"input / output", 0.0}));
}

// Five images on a line; the reference and one run's poses, the run evaluated against it.
struct Figures {
  std::vector<std::string> names = {"f_1.png", "f_2.png", "f_3.png", "f_4.png", "f_5.png"};
  std::map<std::string, Rigid3d> reference;
  std::map<std::string, std::map<std::string, Rigid3d>> poses;
  Comparison comparison;
};

Figures Evaluated() {
  Figures figures;
  for (size_t k = 0; k < figures.names.size(); ++k) {
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitY()));
    figures.reference[figures.names[k]] =
        Rigid3d(turn, -(turn * Eigen::Vector3d(k, 0.3 * k * k, 0)));
  }
  figures.poses["COLMAP"] = figures.reference;
  figures.poses["ramap"] = figures.reference;
  figures.poses["ramap"].erase("f_5.png");  // unregistered
  MapperRun colmap = MakeRun("COLMAP", true, 3.0, {});
  MapperRun ramap = MakeRun("ramap", true, 1.0, {{"rotation averaging", 0.5}});
  ramap.evaluation = EvaluatePoses(figures.poses["ramap"], figures.reference, figures.names);
  figures.comparison.runs = {colmap, ramap};
  return figures;
}

TEST(ComparisonFigures, EvaluatedRunsGetTrajectoryAndErrorFigures) {
  test::TempDir dir;
  Figures figures = Evaluated();
  DrawComparisonFigures(figures.names, figures.reference, false, figures.poses, "line", dir.path(),
                        &figures.comparison);
  const std::vector<std::string> expected = {"trajectories.png", "rotation_error_cdf.png",
                                             "position_error_cdf.png", "stage_times.png"};
  EXPECT_EQ(figures.comparison.figures, expected);
  for (const std::string& name : expected) {
    EXPECT_GT(fs::file_size(dir / name), 1000u) << name;
  }
}

TEST(ComparisonFigures, WithoutEvaluationsOnlyTheStageTimes) {
  test::TempDir dir;
  Figures figures = Evaluated();
  figures.comparison.runs[1].evaluation.reset();
  DrawComparisonFigures(figures.names, figures.reference, true, figures.poses, "line", dir.path(),
                        &figures.comparison);
  EXPECT_EQ(figures.comparison.figures, std::vector<std::string>{"stage_times.png"});
  EXPECT_TRUE(fs::exists(dir / "stage_times.png"));
  EXPECT_FALSE(fs::exists(dir / "trajectories.png"));
}

}  // namespace
}  // namespace ramap
