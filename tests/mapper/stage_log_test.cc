// The stage log: the one progress-line format, stage times summed in the order the stages first
// ran, reports appended, and the observer told of each stage.
#include "ramap/mapper/stage_log.h"

#include <gtest/gtest.h>

#include <sstream>

#include "ramap/util/run_observer.h"

namespace ramap {
namespace {

TEST(StageLog, ProgressLineFormat) {
  std::ostringstream out;
  PrintStageLine(out, "bearings", 1.23456, "2000 keypoints");
  // The stage padded to 22, the seconds with 3 decimals in a width of 8.
  EXPECT_EQ(out.str(), "[ramap] bearings                 1.235 s  2000 keypoints\n");
  std::ostringstream long_stage;
  PrintStageLine(long_stage, "translation averaging", 123.4, "");
  EXPECT_EQ(long_stage.str(), "[ramap] translation averaging  123.400 s  \n");
}

TEST(StageLog, StageTimesAreSummedInTheOrderTheStagesFirstRan) {
  StageReport report;
  std::ostringstream progress;
  RecordStage(stage::kRelativePoses, 1.5, "a", &progress, &report);
  RecordStage(stage::kRotationAveraging, 2.0, "b", nullptr, &report);  // no line
  RecordStage(stage::kRelativePoses, 0.25, "c", &progress, &report);
  ASSERT_EQ(report.timings.size(), 2u);
  EXPECT_EQ(report.timings[0].stage, stage::kRelativePoses);
  EXPECT_EQ(report.timings[0].seconds, 1.75);
  EXPECT_EQ(report.timings[1].stage, stage::kRotationAveraging);
  EXPECT_EQ(report.timings[1].seconds, 2.0);
  std::ostringstream expected;
  PrintStageLine(expected, stage::kRelativePoses, 1.5, "a");
  PrintStageLine(expected, stage::kRelativePoses, 0.25, "c");
  EXPECT_EQ(progress.str(), expected.str());
}

class StageRecorder : public RunObserver {
 public:
  void OnStage(const std::string& stage, double seconds, const std::string& message) override {
    stages.push_back(stage + "|" + std::to_string(seconds) + "|" + message);
  }
  std::vector<std::string> stages;
};

TEST(StageLog, TheRunsObserverIsToldOfEachStage) {
  StageRecorder recorder;
  ScopedRunObserver install(&recorder);
  StageReport report;
  RecordStage(stage::kTriangulation, 0.5, "900 points", nullptr, &report);
  EXPECT_EQ(recorder.stages, std::vector<std::string>{"triangulation|0.500000|900 points"});
}

TEST(StageLog, AppendedReportAddsTimesItemsAndCountsAndItsReasonsWin) {
  StageReport report;
  report.timings = {{stage::kBearings, 1.0}, {stage::kRelativePoses, 2.0}};
  report.dropped_edges = {{"a.png b.png", "no relative pose"}};
  report.prior_outliers = {{"a.png", "12 m from the fit"}};
  report.image_reasons = {{1, "first"}, {2, "kept"}};
  report.num_keyframes = 3;
  report.num_loop_edges = 1;
  StageReport later;
  later.timings = {{stage::kRelativePoses, 0.5}, {stage::kBundleAdjustment, 4.0}};
  later.dropped_edges = {{"c.png d.png", "pruned"}};
  later.prior_outliers = {{"c.png", "no fix"}};
  later.image_reasons = {{1, "later"}, {3, "new"}};
  later.num_keyframes = 2;
  later.num_loop_edges = 5;
  AppendReport(later, &report);

  ASSERT_EQ(report.timings.size(), 3u);
  EXPECT_EQ(report.timings[0].stage, stage::kBearings);
  EXPECT_EQ(report.timings[0].seconds, 1.0);
  EXPECT_EQ(report.timings[1].stage, stage::kRelativePoses);
  EXPECT_EQ(report.timings[1].seconds, 2.5);
  EXPECT_EQ(report.timings[2].stage, stage::kBundleAdjustment);
  EXPECT_EQ(report.timings[2].seconds, 4.0);
  ASSERT_EQ(report.dropped_edges.size(), 2u);
  EXPECT_EQ(report.dropped_edges[0].what, "a.png b.png");
  EXPECT_EQ(report.dropped_edges[1].what, "c.png d.png");
  EXPECT_EQ(report.dropped_edges[1].reason, "pruned");
  ASSERT_EQ(report.prior_outliers.size(), 2u);
  EXPECT_EQ(report.prior_outliers[1].what, "c.png");
  EXPECT_EQ(report.image_reasons,
            (std::map<uint32_t, std::string>{{1, "later"}, {2, "kept"}, {3, "new"}}));
  EXPECT_EQ(report.num_keyframes, 5);
  EXPECT_EQ(report.num_loop_edges, 6);
}

TEST(StageLog, TimedStagesAreTheMappersInTheOrderItRunsThem) {
  EXPECT_EQ(
      TimedMapperStages(),
      (std::vector<std::string>{"bearings", "relative poses", "rotation averaging",
                                "translation averaging", "triangulation", "bundle adjustment"}));
}

TEST(StageLog, AnglesAndDistancesAsSummariesGiveThem) {
  EXPECT_EQ(FormatDegrees(12.345), "12.3 deg");
  EXPECT_EQ(FormatDegrees(0.0), "0.0 deg");
  EXPECT_EQ(FormatMetres(4.567), "4.57 m");
  EXPECT_EQ(FormatMetres(1234.0), "1234.00 m");
}

}  // namespace
}  // namespace ramap
