// `ramap compare --peer_colmap`: the peer rows (COLMAP 4's incremental mapper and GLOMAP) in the
// report, each run on its own copy of the database. A stand-in script plays every COLMAP: it
// records how it was called, changes the database it is given (COLMAP 4 upgrades a 3.8 database in
// place) and writes a known model, the scene's ground truth.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_support.h"

namespace ramap::test {
namespace {

namespace fs = std::filesystem;

// A `colmap` that prints a version for `help` and, for `mapper` or `global_mapper`, appends its
// arguments to CALLS, appends a line to the database it was given when `upgrades_database` (as
// COLMAP 4 changes a 3.8 database) and copies MODEL into OUTPUT_PATH/0.
void WriteStandInColmap(const std::string& path, const std::string& version,
                        const std::string& calls, const std::string& model,
                        bool upgrades_database) {
  std::ofstream script(path);
  script << "#!/bin/sh\n"
         << "if [ \"$1\" = help ]; then echo 'COLMAP " << version << " (stand-in)'; exit 0; fi\n"
         << "echo \"$*\" >> '" << calls
         << "'\n"
         // GLOMAP's stage lines, as its glog output has them.
         << "if [ \"$1\" = global_mapper ]; then\n"
         << "  echo 'I1201 10:00:00.000 7 global_mapper.cc:495] Rotation averaging done in 0.25 "
            "seconds'\n"
         << "  echo 'I1201 10:00:01.000 7 global_pipeline.cc:110] Reconstruction done in 1.5 "
            "seconds'\n"
         << "fi\n"
         << "while [ $# -gt 0 ]; do\n"
         << "  case \"$1\" in\n"
         << "    --database_path) db=$2 ;;\n"
         << "    --output_path) out=$2 ;;\n"
         << "  esac\n"
         << "  shift\n"
         << "done\n"
         << (upgrades_database ? "echo upgraded >> \"$db\"\n" : "") << "mkdir -p \"$out/0\" && cp '"
         << model << "'/*.bin \"$out/0/\"\n";
  script.close();
  fs::permissions(path, fs::perms::owner_all);
}

// The lines of `calls` that ran `command` (a COLMAP sub-command).
std::vector<std::string> CallsOf(const std::string& calls, const std::string& command) {
  std::vector<std::string> found;
  std::istringstream in(test::ReadFileBytes(calls));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(command + " ", 0) == 0) found.push_back(line);
  }
  return found;
}

// A synthetic orbit of `num_images` in FOLDER/scene (database.db, ground_truth/).
void SynthesizeOrbit(const TempDir& dir, int num_images, int seed) {
  const CommandResult synthesize = RunCommand(
      "'" + RamapBinary() + "' synthesize --output_path '" + (dir / "scene") +
      "' --Synthetic.path circle --Synthetic.num_points 800 --Synthetic.pixel_noise 0.3" +
      " --Synthetic.num_images " + std::to_string(num_images) + " --Synthetic.seed " +
      std::to_string(seed));
  ASSERT_EQ(synthesize.exit_code, 0) << synthesize.output;
}

TEST(ComparePeers, ReportHasColmap4AndGlomapRowsRunOnCopiesOfTheDatabase) {
  TempDir dir;
  const std::string ramap = "'" + RamapBinary() + "' ";
  ASSERT_NO_FATAL_FAILURE(SynthesizeOrbit(dir, 12, 3));
  const std::string db = dir / "scene/database.db", gt = dir / "scene/ground_truth";
  const std::string database_before = test::ReadFileBytes(db);
  WriteStandInColmap(dir / "colmap38", "3.8", dir / "calls38.txt", gt, false);
  WriteStandInColmap(dir / "colmap4", "4.1.1", dir / "calls4.txt", gt, true);

  const CommandResult compare =
      RunCommand(ramap + "compare --database_path '" + db + "' --output_path '" + (dir / "cmp") +
                 "' --ground_truth '" + gt + "' --ground_truth_format colmap --colmap_path '" +
                 (dir / "colmap38") + "' --peer_colmap '" + (dir / "colmap4") + "'");
  ASSERT_EQ(compare.exit_code, 0) << compare.output;

  // Five rows in order, the peers' evaluated like the others (their model is the ground truth).
  std::ifstream in(dir / "cmp/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["peer_version"], "4.1.1");
  std::vector<std::string> names;
  for (const nlohmann::json& run : report["runs"]) names.push_back(run["name"]);
  EXPECT_EQ(names,
            (std::vector<std::string>{"COLMAP", "COLMAP 4.1.1", "GLOMAP", "ramap", "ramap+BA"}));
  for (const nlohmann::json& run : report["runs"]) {
    ASSERT_TRUE(run["succeeded"].get<bool>()) << run["name"];
    EXPECT_EQ(run["num_registered"], 12) << run["name"];
    EXPECT_GT(run["speedup_over_glomap"].get<double>(), 0) << run["name"];
    const nlohmann::json& evaluation = run["evaluation"];
    ASSERT_FALSE(evaluation.is_null()) << run["name"];
    if (run["name"] == "COLMAP 4.1.1" || run["name"] == "GLOMAP") {
      EXPECT_LT(evaluation["ate"]["rmse_over_extent"].get<double>(), 1e-9) << run["name"];
      EXPECT_NEAR(evaluation["relative"]["auc_by_threshold_deg"]["1"].get<double>(), 1.0, 1e-9);
    }
  }
  // GLOMAP's stages from its log (its total left out); COLMAP's incremental mapper prints none.
  EXPECT_EQ(report["runs"][2]["stage_seconds"], (nlohmann::json{{"Rotation averaging", 0.25}}));
  EXPECT_FALSE(report["runs"][1].contains("stage_seconds"));
  const std::string markdown = test::ReadFileBytes(dir / "cmp/report.md");
  EXPECT_NE(markdown.find("speed-up over GLOMAP"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("Against GLOMAP (AUC@3 100.0"), std::string::npos) << markdown;

  // The peers ran once each, with intrinsics fixed as COLMAP 3.8 was, on a copy that is gone
  // now; the compared database is untouched.
  const std::vector<std::string> incremental = CallsOf(dir / "calls4.txt", "mapper");
  const std::vector<std::string> global = CallsOf(dir / "calls4.txt", "global_mapper");
  ASSERT_EQ(incremental.size(), 1u);
  ASSERT_EQ(global.size(), 1u);
  EXPECT_NE(incremental[0].find("--Mapper.ba_refine_focal_length 0"), std::string::npos);
  EXPECT_NE(global[0].find("--GlobalMapper.ba_refine_focal_length 0"), std::string::npos);
  for (const std::string& call : {incremental[0], global[0]}) {
    EXPECT_EQ(call.find("--database_path " + db), std::string::npos) << call;
  }
  EXPECT_EQ(CallsOf(dir / "calls38.txt", "mapper").size(), 1u);
  EXPECT_EQ(test::ReadFileBytes(db), database_before);
  for (const fs::directory_entry& entry : fs::directory_iterator(dir / "cmp")) {
    EXPECT_EQ(entry.path().string().find(".database.db"), std::string::npos) << entry.path();
  }
}

TEST(ComparePeers, WithoutAPeerTheReportHasNoPeerRows) {
  TempDir dir;
  const std::string ramap = "'" + RamapBinary() + "' ";
  ASSERT_NO_FATAL_FAILURE(SynthesizeOrbit(dir, 8, 4));
  WriteStandInColmap(dir / "colmap38", "3.8", dir / "calls38.txt", dir / "scene/ground_truth",
                     false);
  const CommandResult compare = RunCommand(
      ramap + "compare --database_path '" + (dir / "scene/database.db") + "' --output_path '" +
      (dir / "cmp") + "' --colmap_path '" + (dir / "colmap38") + "'");
  ASSERT_EQ(compare.exit_code, 0) << compare.output;
  std::ifstream in(dir / "cmp/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["runs"].size(), 3u);
  EXPECT_FALSE(report["runs"][1].contains("speedup_over_glomap"));
  EXPECT_EQ(test::ReadFileBytes(dir / "cmp/report.md").find("GLOMAP"), std::string::npos);
}

}  // namespace
}  // namespace ramap::test
