// One run of a comparison as a process: timed, its output logged, its largest model read once with
// its focal lengths and stage times (ramap's summary.json or GLOMAP's log lines), a peer's database
// copy made and removed, and run folders that hold anything else refused.
#include "ramap/compare/mapper_process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A comparison's folders: the database, and two models of 6 and 4 images of its truth.
struct Folders {
  CompareOptions options;
  SyntheticScene scene;
};

Folders MakeFolders(const test::TempDir& dir) {
  SyntheticSceneOptions scene_options;
  scene_options.num_images = 6;
  scene_options.num_points = 150;
  Folders folders{CompareOptions(), BuildSyntheticScene(scene_options)};
  WriteColmapDatabase(folders.scene.database, dir / "database.db");
  WriteColmapModel(folders.scene.ground_truth, dir / "large", ModelFormat::kBinary);
  Reconstruction small = folders.scene.ground_truth;
  small.images.erase(5);
  small.images.erase(6);
  small.points3D.clear();
  for (auto& [id, image] : small.images) {
    for (Point2D& point : image.points2D) point.point3D_id = kInvalidPoint3DId;
  }
  WriteColmapModel(small, dir / "small", ModelFormat::kBinary);
  folders.options.database_path = dir / "database.db";
  folders.options.output_path = dir / "out";
  fs::create_directories(dir / "out");
  return folders;
}

// A plan whose command runs `body` as one shell script (a plan's command is one program, whose
// output the run redirects into its log).
MapperPlan Plan(const test::TempDir& dir, const std::string& body,
                const std::string& folder = "run") {
  static int count = 0;
  const std::string script = dir / ("stand-in-" + std::to_string(count++) + ".sh");
  std::ofstream(script) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(script, fs::perms::owner_all);
  MapperPlan plan;
  plan.name = "stand-in";
  plan.folder = folder;
  plan.command = "'" + script + "'";
  return plan;
}

TEST(MapperProcess, TheLargestModelWithItsFocalLengthsAndGlomapsStageTimes) {
  test::TempDir dir;
  const Folders folders = MakeFolders(dir);
  const std::string out = folders.options.output_path + "/run";
  // Models 0 (4 images) and 1 (6 images), GLOMAP's stage lines, 0.2 s of work.
  const MapperPlan plan = Plan(
      dir, "mkdir -p '" + out + "/0' '" + out + "/1' && cp '" + (dir / "small") + "'/* '" + out +
               "/0/' && cp '" + (dir / "large") + "'/* '" + out + "/1/' && sleep 0.2 && " +
               "echo 'I1201 global_mapper.cc:495] Rotation averaging done in 0.25 seconds' && " +
               "echo 'I1201 global_mapper.cc:500] Global positioning done in 1e-1 seconds' && " +
               "echo 'I1201 global_pipeline.cc:110] Reconstruction done in 1.5 seconds'");
  Reconstruction model;
  const MapperRun run = RunMapperPlan(plan, folders.options, 6, &model);
  EXPECT_TRUE(run.succeeded);
  EXPECT_EQ(run.name, "stand-in");
  EXPECT_EQ(run.command, plan.command);
  EXPECT_EQ(run.num_models, 2);
  EXPECT_EQ(run.num_registered, 6);
  EXPECT_EQ(run.model_path, out + "/1");
  EXPECT_EQ(model.images.size(), 6u);
  EXPECT_GE(run.seconds, 0.2);  // the whole process, timed
  EXPECT_EQ(run.focal_lengths_px, (std::map<uint32_t, double>{{1, 500.0}}));
  // The stages GLOMAP logged, its sum ("Reconstruction") left out.
  EXPECT_EQ(run.stage_seconds, (std::vector<std::pair<std::string, double>>{
                                   {"Rotation averaging", 0.25}, {"Global positioning", 0.1}}));
  EXPECT_TRUE(fs::exists(out + ".log"));
}

TEST(MapperProcess, RamapsStageTimesComeFromItsSummary) {
  test::TempDir dir;
  const Folders folders = MakeFolders(dir);
  const std::string out = folders.options.output_path + "/run";
  std::ofstream(dir / "summary.json")
      << R"({"stage_seconds": {"bundle adjustment": 2.0, "bearings": 0.5, "other": 9}})";
  const MapperPlan plan =
      Plan(dir, "mkdir -p '" + out + "/0' && cp '" + (dir / "large") + "'/* '" + out +
                    "/0/' && cp '" + (dir / "summary.json") + "' '" + out + "/'");
  Reconstruction model;
  const MapperRun run = RunMapperPlan(plan, folders.options, 6, &model);
  EXPECT_TRUE(run.succeeded);
  // The mapper's timed stages, in the order it runs them.
  EXPECT_EQ(run.stage_seconds, (std::vector<std::pair<std::string, double>>{
                                   {"bearings", 0.5}, {"bundle adjustment", 2.0}}));
}

TEST(MapperProcess, AFailedProcessOrNoModelIsAFailedRun) {
  test::TempDir dir;
  const Folders folders = MakeFolders(dir);
  Reconstruction model;
  const MapperRun failed =
      RunMapperPlan(Plan(dir, "echo broken && exit 3"), folders.options, 6, &model);
  EXPECT_FALSE(failed.succeeded);
  EXPECT_TRUE(model.images.empty());
  EXPECT_EQ(test::ReadFileBytes(folders.options.output_path + "/run.log"), "broken\n");
  const MapperRun empty = RunMapperPlan(Plan(dir, "true"), folders.options, 6, &model);
  EXPECT_FALSE(empty.succeeded);
  EXPECT_EQ(empty.num_models, 0);
}

TEST(MapperProcess, APeersCopyIsMadeForTheRunAndRemovedAfter) {
  test::TempDir dir;
  const Folders folders = MakeFolders(dir);
  MapperPlan plan = Plan(dir, "cp '" + (dir / "out/copy.db") + "' '" + (dir / "seen.db") + "'");
  plan.on_database_copy = true;
  plan.database_path = dir / "out/copy.db";
  Reconstruction model;
  RunMapperPlan(plan, folders.options, 6, &model);
  EXPECT_EQ(test::ReadFileBytes(dir / "seen.db"), test::ReadFileBytes(dir / "database.db"));
  EXPECT_FALSE(fs::exists(dir / "out/copy.db"));
  // As a COLMAP 3.8 database: rewritten, and read back the same images.
  plan.copy_as_colmap38 = true;
  fs::remove(dir / "seen.db");
  RunMapperPlan(plan, folders.options, 6, &model);
  EXPECT_EQ(ReadDatabaseImageNames(dir / "seen.db"), ReadDatabaseImageNames(dir / "database.db"));
  EXPECT_FALSE(fs::exists(dir / "out/copy.db"));
}

TEST(MapperProcess, RunFoldersHoldingAnythingElseAreRefused) {
  test::TempDir dir;
  const Folders folders = MakeFolders(dir);
  const std::string out = folders.options.output_path;
  // An earlier run's output may be replaced.
  fs::create_directories(out + "/run/0");
  fs::copy(dir / "large", out + "/run/0", fs::copy_options::recursive);
  EXPECT_NO_THROW(CheckRunFolder(out, Plan(dir, "true"), folders.options.database_path));
  // A user's file in it may not.
  std::ofstream(out + "/run/notes.txt") << "mine";
  test::ExpectInputError(
      [&] { CheckRunFolder(out, Plan(dir, "true"), folders.options.database_path); },
      {"--output_path", "notes.txt"});
  fs::create_directories(out + "/other.log");
  test::ExpectInputError(
      [&] { CheckRunFolder(out, Plan(dir, "true", "other"), folders.options.database_path); },
      {"other.log is a folder"});
  // A peer's copy may not be the compared database itself.
  MapperPlan peer = Plan(dir, "true", "peer");
  peer.on_database_copy = true;
  peer.database_path = folders.options.database_path;
  test::ExpectInputError([&] { CheckRunFolder(out, peer, folders.options.database_path); },
                         {"is the compared database"});
}

}  // namespace
}  // namespace ramap
