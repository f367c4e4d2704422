// The comparison's mapper runs as command lines: report order, each mapper's options of the same
// meaning, peers on copies of the database (COLMAP 3.8 on a 3.8 copy of a later generation),
// shell quoting that survives any path, and a COLMAP binary's version.
#include "ramap/compare/mapper_plans.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ramap/io/colmap_database.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

CompareOptions Options(const test::TempDir& dir, DatabaseGeneration generation) {
  SyntheticSceneOptions scene;
  scene.num_images = 4;
  scene.num_points = 100;
  WriteColmapDatabase(BuildSyntheticScene(scene).database, dir / "database.db", generation);
  CompareOptions options;
  options.database_path = dir / "database.db";
  options.output_path = dir / "out";
  options.image_path = dir / "images";
  options.colmap_binary = "/opt/colmap 3.8/colmap";
  options.ramap_binary = "/opt/ramap";
  options.num_threads = 3;
  return options;
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MapperPlans, ColmapThenRamapWithAndWithoutBundleAdjustment) {
  test::TempDir dir;
  const CompareOptions options = Options(dir, DatabaseGeneration::kColmap38);
  const std::vector<MapperPlan> plans = MapperPlans(options, "");
  ASSERT_EQ(plans.size(), 3u);
  EXPECT_EQ(plans[0].name, "COLMAP");
  EXPECT_EQ(plans[1].name, "ramap");
  EXPECT_EQ(plans[2].name, "ramap+BA");
  EXPECT_EQ(plans[0].folder, "colmap");
  EXPECT_EQ(plans[1].folder, "ramap");
  EXPECT_EQ(plans[2].folder, "ramap_ba");
  // A 3.8 database is every run's own: no copy.
  for (const MapperPlan& plan : plans) {
    EXPECT_EQ(plan.database_path, options.database_path) << plan.name;
    EXPECT_FALSE(plan.on_database_copy) << plan.name;
  }
  const std::string& colmap = plans[0].command;
  EXPECT_EQ(
      colmap.rfind(
          "'/opt/colmap 3.8/colmap' mapper --database_path '" + options.database_path + "'", 0),
      0u)
      << colmap;
  EXPECT_TRUE(Contains(colmap, "--output_path '" + options.output_path + "/colmap'")) << colmap;
  EXPECT_TRUE(Contains(colmap, "--image_path '" + options.image_path + "'")) << colmap;
  EXPECT_TRUE(Contains(colmap, "--Mapper.num_threads 3")) << colmap;
  // Intrinsics fixed in every mapper unless asked to refine them.
  for (const char* what : {"focal_length", "principal_point", "extra_params"}) {
    EXPECT_TRUE(Contains(colmap, std::string("--Mapper.ba_refine_") + what + " 0")) << colmap;
    for (size_t k = 1; k < 3; ++k) {
      EXPECT_TRUE(
          Contains(plans[k].command, std::string("--BundleAdjustment.refine_") + what + " 0"))
          << plans[k].command;
    }
  }
  EXPECT_EQ(plans[1].command.rfind("'/opt/ramap' mapper ", 0), 0u) << plans[1].command;
  EXPECT_TRUE(Contains(plans[1].command, "--Mapper.refine 0"));
  EXPECT_TRUE(Contains(plans[2].command, "--Mapper.refine 1"));
  EXPECT_TRUE(Contains(plans[2].command, "--Mapper.num_threads 3"));
  EXPECT_TRUE(Contains(plans[2].command, "--output_path '" + options.output_path + "/ramap_ba'"));

  CompareOptions refine = options;
  refine.refine_intrinsics = true;
  for (const MapperPlan& plan : MapperPlans(refine, "")) {
    EXPECT_FALSE(Contains(plan.command, "refine_focal_length")) << plan.command;
  }
}

TEST(MapperPlans, PeersRunOnCopiesAndColmapThreeEightOnAThreeEightCopy) {
  test::TempDir dir;
  CompareOptions options = Options(dir, DatabaseGeneration::kColmap4);
  options.peer_colmap_binary = "/opt/colmap4";
  const std::vector<MapperPlan> plans = MapperPlans(options, "4.1.1");
  ASSERT_EQ(plans.size(), 5u);
  const std::vector<std::string> names = {"COLMAP", "COLMAP 4.1.1", "GLOMAP", "ramap", "ramap+BA"};
  for (size_t k = 0; k < names.size(); ++k) EXPECT_EQ(plans[k].name, names[k]);
  // COLMAP 3.8 reads no 4.x database: a 3.8 copy in the output folder.
  EXPECT_TRUE(plans[0].on_database_copy);
  EXPECT_TRUE(plans[0].copy_as_colmap38);
  EXPECT_EQ(plans[0].database_path, options.output_path + "/colmap.database.db");
  EXPECT_TRUE(Contains(plans[0].command, "--database_path '" + plans[0].database_path + "'"));
  // Each peer on a byte copy of its own (COLMAP 4 upgrades what it opens).
  EXPECT_TRUE(plans[1].on_database_copy);
  EXPECT_FALSE(plans[1].copy_as_colmap38);
  EXPECT_TRUE(plans[2].on_database_copy);
  EXPECT_NE(plans[1].database_path, plans[2].database_path);
  EXPECT_EQ(plans[1].command.rfind("'/opt/colmap4' mapper ", 0), 0u) << plans[1].command;
  EXPECT_EQ(plans[2].command.rfind("'/opt/colmap4' global_mapper ", 0), 0u) << plans[2].command;
  EXPECT_TRUE(Contains(plans[2].command, "--GlobalMapper.num_threads 3"));
  EXPECT_TRUE(Contains(plans[2].command, "--GlobalMapper.ba_refine_focal_length 0"));
  // ramap reads the database as it is.
  EXPECT_EQ(plans[3].database_path, options.database_path);
  EXPECT_FALSE(plans[3].on_database_copy);
}

TEST(MapperPlans, ShellQuotingSurvivesAnyPath) {
  for (const std::string text :
       {std::string("plain"), std::string("with space"), std::string("it's"),
        std::string("$HOME `x` \"q\" \\ ;|&"), std::string("")}) {
    const test::CommandResult echoed = test::RunCommand("printf %s " + ShellQuote(text));
    EXPECT_EQ(echoed.exit_code, 0);
    EXPECT_EQ(echoed.output, text);
  }
}

TEST(MapperPlans, ColmapVersionFromItsHelp) {
  test::TempDir dir;
  const auto stand_in = [&](const std::string& name, const std::string& help) {
    std::ofstream(dir / name) << "#!/bin/sh\necho '" << help << "'\n";
    fs::permissions(dir / name, fs::perms::owner_all);
    return dir / name;
  };
  EXPECT_EQ(ColmapVersion(stand_in("four", "COLMAP 4.1.1 (Commit abc on 2025-01-01)")), "4.1.1");
  EXPECT_EQ(ColmapVersion(stand_in("dev", "COLMAP 3.13.0.dev0 -- Structure-from-Motion")),
            "3.13.0");
  EXPECT_EQ(ColmapVersion(stand_in("other", "usage: something else")), "peer");
  EXPECT_EQ(ColmapVersion(dir / "missing"), "peer");
}

}  // namespace
}  // namespace ramap
