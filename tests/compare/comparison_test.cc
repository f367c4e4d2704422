// The comparison report from plain data: speed ratios over COLMAP and over GLOMAP, and the
// ratio line against GLOMAP at each mapper's AUC@3.
#include "ramap/compare/comparison.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

MapperRun EvaluatedRun(const std::string& name, double seconds, double auc3) {
  MapperRun run;
  run.name = name;
  run.succeeded = true;
  run.seconds = seconds;
  run.num_registered = 10;
  PoseEvaluation evaluation;
  evaluation.auc_thresholds_deg = {1, 3, 5, 10};
  evaluation.auc = {0.5 * auc3, auc3, 1.0, 1.0};
  run.evaluation = evaluation;
  return run;
}

TEST(Comparison, SpeedRatiosOverColmapAndGlomap) {
  Comparison comparison;
  comparison.num_images = 10;
  comparison.runs = {
      EvaluatedRun(mapper_row::kColmap, 40, 0.90), EvaluatedRun(mapper_row::kGlomap, 20, 0.95),
      EvaluatedRun(mapper_row::kRamap, 1, 0.80), EvaluatedRun(mapper_row::kRamapBa, 2, 0.96)};
  const nlohmann::json json = ComparisonToJson(comparison);
  EXPECT_DOUBLE_EQ(json["runs"][0]["speedup_over_colmap"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(json["runs"][3]["speedup_over_colmap"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(json["runs"][3]["speedup_over_glomap"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(json["runs"][0]["speedup_over_glomap"].get<double>(), 0.5);

  const std::string markdown = ComparisonToMarkdown(comparison);
  EXPECT_NE(markdown.find("| speed-up over COLMAP | speed-up over GLOMAP |"), std::string::npos);
  EXPECT_NE(markdown.find("Against GLOMAP (AUC@3 95.0, 20.00 s): ramap 20.0x as fast at AUC@3 "
                          "80.0; ramap+BA 10.0x as fast at AUC@3 96.0."),
            std::string::npos)
      << markdown;
}

TEST(Comparison, AFailedGlomapGivesNoRatiosAndNoPeerGivesNoColumn) {
  Comparison comparison;
  comparison.runs = {EvaluatedRun(mapper_row::kColmap, 40, 0.9),
                     EvaluatedRun(mapper_row::kGlomap, 20, 0.9),
                     EvaluatedRun(mapper_row::kRamapBa, 2, 0.9)};
  comparison.runs[1].succeeded = false;
  const nlohmann::json json = ComparisonToJson(comparison);
  EXPECT_TRUE(json["runs"][2]["speedup_over_glomap"].is_null());
  EXPECT_NE(ComparisonToMarkdown(comparison).find("GLOMAP failed: no ratios against it."),
            std::string::npos);

  comparison.runs.erase(comparison.runs.begin() + 1);
  EXPECT_FALSE(ComparisonToJson(comparison)["runs"][1].contains("speedup_over_glomap"));
  EXPECT_EQ(ComparisonToMarkdown(comparison).find("GLOMAP"), std::string::npos);
}

}  // namespace
}  // namespace ramap
