// CompareMappers on a synthetic scene with stand-in mappers (each writes the scene's truth as its
// model): every run evaluated against the ground truth, the reports and figures written, the
// options and folders checked before anything runs, and a failed run named after the reports.
#include "ramap/compare/compare_mappers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A mapper that appends its arguments to CALLS and writes MODEL to OUTPUT_PATH/0 (or exits 1 when
// `fails`); COLMAP's and ramap's command lines both name --output_path.
void WriteStandIn(const std::string& path, const std::string& calls, const std::string& model,
                  bool fails = false) {
  std::ofstream script(path);
  script << "#!/bin/sh\n"
         << "if [ \"$1\" = help ]; then echo 'COLMAP 3.8 (stand-in)'; exit 0; fi\n"
         << "echo \"$*\" >> '" << calls << "'\n"
         << (fails ? "echo 'stand-in failure'; exit 1\n" : "") << "while [ $# -gt 0 ]; do\n"
         << "  if [ \"$1\" = --output_path ]; then out=$2; fi\n"
         << "  shift\n"
         << "done\n"
         << "mkdir -p \"$out/0\" && cp '" << model << "'/*.bin \"$out/0/\"\n";
  script.close();
  fs::permissions(path, fs::perms::owner_all);
}

// A noise-free 8-frame line: its database, its truth as a COLMAP model (the ground truth), and
// stand-ins for COLMAP and ramap.
CompareOptions Scene(const test::TempDir& dir) {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 8);
  options.num_points = 200;
  const SyntheticScene scene = BuildSyntheticScene(options);
  fs::create_directories(dir / "scene");
  WriteColmapDatabase(scene.database, dir / "scene/database.db");
  WriteColmapModel(scene.ground_truth, dir / "scene/truth", ModelFormat::kBinary);
  WriteStandIn(dir / "colmap", dir / "colmap_calls.txt", dir / "scene/truth");
  WriteStandIn(dir / "ramap", dir / "ramap_calls.txt", dir / "scene/truth");
  CompareOptions compare;
  compare.database_path = dir / "scene/database.db";
  compare.output_path = dir / "out";
  compare.ground_truth_path = dir / "scene/truth";
  compare.ground_truth_format = "colmap";
  compare.colmap_binary = dir / "colmap";
  compare.ramap_binary = dir / "ramap";
  return compare;
}

TEST(CompareMappers, EveryRunEvaluatedAgainstTheGroundTruthAndReported) {
  test::TempDir dir;
  CompareOptions options = Scene(dir);
  options.png_figures = true;
  const Comparison comparison = CompareMappers(options);
  EXPECT_EQ(comparison.num_images, 8);
  EXPECT_EQ(comparison.reference, "ground truth " + options.ground_truth_path + " (colmap)");
  ASSERT_EQ(comparison.runs.size(), 3u);
  for (const MapperRun& run : comparison.runs) {
    EXPECT_TRUE(run.succeeded) << run.name;
    EXPECT_EQ(run.num_registered, 8) << run.name;
    ASSERT_TRUE(run.evaluation.has_value()) << run.name;
    // Each wrote the truth itself: float64 model files, rounding only.
    EXPECT_LT(run.evaluation->rotation_error_max_deg, 1e-6) << run.name;
  }
  // Each mapper ran once: COLMAP, then ramap without and with bundle adjustment.
  const std::string colmap_calls = test::ReadFileBytes(dir / "colmap_calls.txt");
  EXPECT_EQ(std::count(colmap_calls.begin(), colmap_calls.end(), '\n'), 1);
  const std::string ramap_calls = test::ReadFileBytes(dir / "ramap_calls.txt");
  EXPECT_NE(ramap_calls.find("--Mapper.refine 0"), std::string::npos) << ramap_calls;
  EXPECT_NE(ramap_calls.find("--Mapper.refine 1"), std::string::npos) << ramap_calls;
  // The reports and the figures asked for; an image folder made for COLMAP when none was given.
  const nlohmann::json report = test::ReadJsonFile(dir / "out/report.json");
  EXPECT_EQ(report["runs"].size(), 3u);
  EXPECT_NE(test::ReadFileBytes(dir / "out/report.md").find("ramap+BA"), std::string::npos);
  EXPECT_FALSE(test::ReportPageData(dir / "out/report.html").is_null());
  EXPECT_EQ(comparison.figures.size(), 4u);
  for (const std::string& figure : comparison.figures) {
    EXPECT_TRUE(fs::exists(dir / ("out/" + figure))) << figure;
  }
  EXPECT_TRUE(fs::is_directory(dir / "out/no_images"));
}

TEST(CompareMappers, OptionsAndFoldersAreCheckedBeforeAnythingRuns) {
  test::TempDir dir;
  const CompareOptions options = Scene(dir);
  CompareOptions no_format = options;
  no_format.ground_truth_format.clear();
  test::ExpectInputError([&] { CompareMappers(no_format); },
                         {"--ground_truth", "--ground_truth_format"});
  CompareOptions no_colmap = options;
  no_colmap.colmap_binary = dir / "no_such_colmap";
  test::ExpectInputError([&] { CompareMappers(no_colmap); }, {"--colmap_path", "no such file"});
  // A run folder holding a user's file.
  fs::create_directories(dir / "out/ramap");
  std::ofstream(dir / "out/ramap/notes.txt") << "mine";
  test::ExpectInputError([&] { CompareMappers(options); }, {"--output_path", "notes.txt"});
  // Nothing ran, and the user's folder is as it was.
  EXPECT_FALSE(fs::exists(dir / "colmap_calls.txt"));
  EXPECT_FALSE(fs::exists(dir / "ramap_calls.txt"));
  EXPECT_EQ(test::ReadFileBytes(dir / "out/ramap/notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(dir / "out/report.json"));
}

TEST(CompareMappers, AFailedRunIsNamedAfterTheReportsAreWritten) {
  test::TempDir dir;
  CompareOptions options = Scene(dir);
  WriteStandIn(dir / "colmap", dir / "colmap_calls.txt", dir / "scene/truth", /*fails=*/true);
  test::ExpectInputError([&] { CompareMappers(options); }, {"COLMAP failed", ".log"});
  const nlohmann::json report = test::ReadJsonFile(dir / "out/report.json");
  ASSERT_EQ(report["runs"].size(), 3u);
  EXPECT_EQ(report["runs"][0]["succeeded"], false);
  EXPECT_EQ(report["runs"][1]["succeeded"], true);
  EXPECT_NE(test::ReadFileBytes(dir / "out/colmap.log").find("stand-in failure"),
            std::string::npos);
}

}  // namespace
}  // namespace ramap
