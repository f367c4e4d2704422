// The generations of COLMAP's database schema: how to tell them apart and how to create each.
//
// Told apart by their tables and columns, never by a version string (COLMAP 4 stamps a database it
// opens with its own user_version and keeps the old columns):
//  - 3.8-3.9: pose priors are the images table's prior_qw..prior_tz columns;
//  - 3.10-3.11: a pose_priors table keyed by image_id (position, coordinate_system, and from 3.11
//    position_covariance);
//  - 3.12-4.x: tables rigs, rig_sensors, frames and frame_data; pose_priors keyed by sensor data
//    (corr_data_id, corr_sensor_id, corr_sensor_type; 3.12-3.13 still keyed it by image_id) with
//    gravity; descriptors.type. A 3.8 database that COLMAP 4 upgraded in place holds both the old
//    prior columns and the new tables.
// The layouts follow COLMAP 4.1.1's src/colmap/scene/database_sqlite.cc and the 3.8 and 3.11
// releases' database.cc.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "ramap/io/sqlite.h"
#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

// "3.8", "3.10", "4" (as --Database.generation takes them).
std::string DatabaseGenerationName(DatabaseGeneration generation);
// The generation named `name` ("3.8", "3.10", "4"; "3.9", "3.11", "4.x" and the like too);
// throws InputError naming `option` otherwise.
DatabaseGeneration DatabaseGenerationFromName(const std::string& name, const std::string& option);
// "COLMAP 3.8-3.9", "COLMAP 3.10-3.11", "COLMAP 3.12-4.x": for logs and summaries.
std::string DatabaseGenerationLabel(DatabaseGeneration generation);

// --Database.generation, for any settings struct that holds the generation of a database it
// writes: COLMAP's version names as DatabaseGenerationFromName reads them (3.9, 4.x, 4.1.1, ...),
// a choice of three schemas under many names.
template <typename Settings, typename Access>
OptionDeclaration<Settings> DatabaseGenerationOption(Access access) {
  OptionDeclaration<Settings> d;
  d.name = "Database.generation";
  d.type = OptionType::kText;
  d.choices = {"3.8", "3.10", "4"};
  d.help =
      "schema of the database written: 3.8 (COLMAP 3.8-3.9, read by every COLMAP), 3.10 "
      "(3.10-3.11) or 4 (3.12-4.x)";
  d.check = [](const std::string& text) -> std::string {
    try {
      DatabaseGenerationFromName(text, "--Database.generation");
    } catch (const InputError&) {
      return "'" + text + "' is not 3.8, 3.10 or 4 (COLMAP 3.8-3.9, 3.10-3.11, 3.12-4.x)";
    }
    return "";
  };
  d.text = [access](const Settings& s) { return DatabaseGenerationName(access(s)); };
  d.store = [access](Settings& s, const std::string& text) {
    access(s) = DatabaseGenerationFromName(text, "--Database.generation");
  };
  return d;
}

enum class PosePriorTable {
  kNone,          // no pose_priors table (3.8-3.9)
  kByImage,       // pose_priors(image_id, position, coordinate_system[, position_covariance])
  kBySensorData,  // pose_priors(pose_prior_id, corr_data_id, corr_sensor_id, corr_sensor_type, ...)
};

// What a database holds, as far as reading it depends on the generation.
struct DatabaseLayout {
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
  bool image_prior_columns = false;  // images.prior_qw .. prior_tz
  PosePriorTable pose_priors = PosePriorTable::kNone;
  bool pose_prior_covariance = false;  // pose_priors.position_covariance
  bool pose_prior_gravity = false;     // pose_priors.gravity
  bool rigs_and_frames = false;        // rigs, rig_sensors, frames, frame_data
  int user_version = 0;                // PRAGMA user_version, informative only
};

// The column names of `table`; empty when there is no such table.
std::set<std::string> TableColumns(sqlite::Connection& db, const std::string& table);

// The layout of the open database. Throws InputError naming the database (db.source()) and the
// missing table or column when it is of no generation ramap knows.
DatabaseLayout DetectDatabaseLayout(sqlite::Connection& db);

// The statements that create an empty database of `generation`, and the user_version it is
// stamped with (3800, 3110000, 4010100: what COLMAP 3.8, 3.11 and 4.1.1 write).
const std::vector<std::string>& SchemaStatements(DatabaseGeneration generation);
int SchemaUserVersion(DatabaseGeneration generation);

}  // namespace ramap
