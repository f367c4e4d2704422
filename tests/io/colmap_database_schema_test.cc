// The schema generations: the layout each generation's own statements create is detected as that
// generation, partial or foreign layouts are named, and the generation names read as documented.
#include "ramap/io/colmap_database_schema.h"

#include <gtest/gtest.h>

#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

using sqlite::Connection;

// An empty database of `generation`, made from SchemaStatements and stamped as COLMAP would.
void CreateEmpty(const std::string& path, DatabaseGeneration generation) {
  Connection db(path, Connection::Create(), path);
  for (const std::string& statement : SchemaStatements(generation)) db.Execute(statement);
  db.Execute("PRAGMA user_version = " + std::to_string(SchemaUserVersion(generation)));
}

DatabaseLayout LayoutOf(const std::string& path) {
  Connection db(path, Connection::OpenExisting(), path);
  return DetectDatabaseLayout(db);
}

TEST(ColmapDatabaseSchema, EachGenerationsSchemaIsDetectedAsIt) {
  test::TempDir dir;
  CreateEmpty(dir / "38.db", DatabaseGeneration::kColmap38);
  const DatabaseLayout v38 = LayoutOf(dir / "38.db");
  EXPECT_EQ(v38.generation, DatabaseGeneration::kColmap38);
  EXPECT_TRUE(v38.image_prior_columns);
  EXPECT_EQ(v38.pose_priors, PosePriorTable::kNone);
  EXPECT_FALSE(v38.rigs_and_frames);
  EXPECT_EQ(v38.user_version, 3800);

  CreateEmpty(dir / "310.db", DatabaseGeneration::kColmap310);
  const DatabaseLayout v310 = LayoutOf(dir / "310.db");
  EXPECT_EQ(v310.generation, DatabaseGeneration::kColmap310);
  EXPECT_FALSE(v310.image_prior_columns);
  EXPECT_EQ(v310.pose_priors, PosePriorTable::kByImage);
  EXPECT_TRUE(v310.pose_prior_covariance);  // 3.11's form
  EXPECT_FALSE(v310.pose_prior_gravity);
  EXPECT_FALSE(v310.rigs_and_frames);
  EXPECT_EQ(v310.user_version, 3110000);

  CreateEmpty(dir / "4.db", DatabaseGeneration::kColmap4);
  const DatabaseLayout v4 = LayoutOf(dir / "4.db");
  EXPECT_EQ(v4.generation, DatabaseGeneration::kColmap4);
  EXPECT_FALSE(v4.image_prior_columns);
  EXPECT_EQ(v4.pose_priors, PosePriorTable::kBySensorData);
  EXPECT_TRUE(v4.pose_prior_covariance);
  EXPECT_TRUE(v4.pose_prior_gravity);
  EXPECT_TRUE(v4.rigs_and_frames);
  EXPECT_EQ(v4.user_version, 4010100);
}

TEST(ColmapDatabaseSchema, TheVersionStampDecidesNothing) {
  // A 3.8 schema stamped by COLMAP 4 is still read as 3.8: tables and columns decide.
  test::TempDir dir;
  CreateEmpty(dir / "38.db", DatabaseGeneration::kColmap38);
  Connection(dir / "38.db", Connection::OpenExisting(), "")
      .Execute("PRAGMA user_version = 4010100");
  const DatabaseLayout layout = LayoutOf(dir / "38.db");
  EXPECT_EQ(layout.generation, DatabaseGeneration::kColmap38);
  EXPECT_EQ(layout.user_version, 4010100);  // informative only
}

TEST(ColmapDatabaseSchema, TableColumnsAreTheTablesOwnOrNone) {
  test::TempDir dir;
  CreateEmpty(dir / "4.db", DatabaseGeneration::kColmap4);
  Connection db(dir / "4.db", Connection::OpenExisting(), "4.db");
  EXPECT_EQ(TableColumns(db, "frames"), (std::set<std::string>{"frame_id", "rig_id"}));
  EXPECT_EQ(TableColumns(db, "images"), (std::set<std::string>{"image_id", "name", "camera_id"}));
  EXPECT_TRUE(TableColumns(db, "no_such_table").empty());
}

TEST(ColmapDatabaseSchema, LayoutsOfNoKnownGenerationAreNamed) {
  test::TempDir dir;
  {
    Connection db(dir / "empty.db", Connection::Create(), "");
    db.Execute("CREATE TABLE other (x)");
  }
  test::ExpectInputError([&] { LayoutOf(dir / "empty.db"); },
                         {"empty.db", "missing table 'cameras'"});

  // Rigs without frames: a damaged 4.x database.
  CreateEmpty(dir / "frames.db", DatabaseGeneration::kColmap4);
  Connection(dir / "frames.db", Connection::OpenExisting(), "").Execute("DROP TABLE frames");
  test::ExpectInputError([&] { LayoutOf(dir / "frames.db"); },
                         {"frames.db", "missing table 'frames'", "beside table"});

  // A pose_priors table keyed by neither images nor sensor data.
  CreateEmpty(dir / "priors.db", DatabaseGeneration::kColmap310);
  {
    Connection db(dir / "priors.db", Connection::OpenExisting(), "");
    db.Execute("DROP TABLE pose_priors");
    db.Execute("CREATE TABLE pose_priors (prior_key INTEGER, position BLOB)");
  }
  test::ExpectInputError([&] { LayoutOf(dir / "priors.db"); },
                         {"priors.db", "table 'pose_priors'", "'corr_data_id'", "'image_id'"});

  // A 3.8 images table without its prior columns, and nothing newer.
  CreateEmpty(dir / "images.db", DatabaseGeneration::kColmap310);
  Connection(dir / "images.db", Connection::OpenExisting(), "").Execute("DROP TABLE pose_priors");
  test::ExpectInputError([&] { LayoutOf(dir / "images.db"); },
                         {"images.db", "'prior_qw'", "'pose_priors'", "'frames'"});
}

TEST(ColmapDatabaseSchema, GenerationNamesAndLabels) {
  EXPECT_EQ(DatabaseGenerationName(DatabaseGeneration::kColmap38), "3.8");
  EXPECT_EQ(DatabaseGenerationName(DatabaseGeneration::kColmap310), "3.10");
  EXPECT_EQ(DatabaseGenerationName(DatabaseGeneration::kColmap4), "4");
  EXPECT_EQ(DatabaseGenerationLabel(DatabaseGeneration::kColmap38), "COLMAP 3.8-3.9");
  EXPECT_EQ(DatabaseGenerationLabel(DatabaseGeneration::kColmap310), "COLMAP 3.10-3.11");
  EXPECT_EQ(DatabaseGenerationLabel(DatabaseGeneration::kColmap4), "COLMAP 3.12-4.x");
  // COLMAP's release names of each generation.
  const std::vector<std::pair<std::string, DatabaseGeneration>> names = {
      {"3.9", DatabaseGeneration::kColmap38}, {"3.11", DatabaseGeneration::kColmap310},
      {"3.12", DatabaseGeneration::kColmap4}, {"3.13", DatabaseGeneration::kColmap4},
      {"4.x", DatabaseGeneration::kColmap4},  {"4.1.1", DatabaseGeneration::kColmap4},
      {"4.X", DatabaseGeneration::kColmap4}};
  for (const auto& [name, generation] : names) {
    EXPECT_EQ(DatabaseGenerationFromName(name, "--x"), generation) << name;
  }
  for (const std::string bad : {"3.7", "5", "", "four"}) {
    test::ExpectInputError([&] { DatabaseGenerationFromName(bad, "--Database.generation"); },
                           {"--Database.generation", "'" + bad + "'"});
  }
}

TEST(ColmapDatabaseSchema, GenerationOptionTakesTheNamesAndStoresTheGeneration) {
  struct Settings {
    DatabaseGeneration generation = DatabaseGeneration::kColmap38;
  };
  const OptionDeclaration<Settings> option =
      DatabaseGenerationOption<Settings>([](auto& s) -> auto& { return s.generation; });
  EXPECT_EQ(option.name, "Database.generation");
  Settings settings;
  EXPECT_EQ(option.text(settings), "3.8");
  SetOption(option, "4.1.1", &settings);
  EXPECT_EQ(settings.generation, DatabaseGeneration::kColmap4);
  EXPECT_EQ(option.text(settings), "4");
  test::ExpectInputError([&] { SetOption(option, "2.0", &settings); },
                         {"--Database.generation", "'2.0' is not 3.8, 3.10 or 4"});
  EXPECT_EQ(settings.generation, DatabaseGeneration::kColmap4);
}

}  // namespace
}  // namespace ramap
