#include "ramap/io/colmap_database_schema.h"

#include <algorithm>
#include <cctype>

#include "ramap/util/error.h"

namespace ramap {
namespace {

// COLMAP 3.8's schema, text for text as `colmap database_creator` leaves it in sqlite_master
// (SQLite keeps the statement as written, minus COLMAP's IF NOT EXISTS), so that a schema dump of
// our database and of COLMAP's are identical.
const std::vector<std::string> kSchema38 = {
    "CREATE TABLE cameras   (camera_id            INTEGER  PRIMARY KEY AUTOINCREMENT  NOT NULL,    "
    "model                INTEGER                             NOT NULL,    width                "
    "INTEGER                             NOT NULL,    height               INTEGER               "
    "              NOT NULL,    params               BLOB,    prior_focal_length   INTEGER       "
    "                      NOT NULL)",
    "CREATE TABLE images   (image_id   INTEGER  PRIMARY KEY AUTOINCREMENT  NOT NULL,    name       "
    "TEXT                                NOT NULL UNIQUE,    camera_id  INTEGER                   "
    "          NOT NULL,    prior_qw   REAL,    prior_qx   REAL,    prior_qy   REAL,    prior_qz   "
    "REAL,    prior_tx   REAL,    prior_ty   REAL,    prior_tz   REAL,CONSTRAINT image_id_check "
    "CHECK(image_id >= 0 and image_id < 2147483647),FOREIGN KEY(camera_id) REFERENCES "
    "cameras(camera_id))",
    "CREATE UNIQUE INDEX index_name ON images(name)",
    "CREATE TABLE keypoints   (image_id  INTEGER  PRIMARY KEY  NOT NULL,    rows      INTEGER     "
    "          NOT NULL,    cols      INTEGER               NOT NULL,    data      BLOB,FOREIGN "
    "KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE)",
    "CREATE TABLE descriptors   (image_id  INTEGER  PRIMARY KEY  NOT NULL,    rows      INTEGER   "
    "            NOT NULL,    cols      INTEGER               NOT NULL,    data      BLOB,FOREIGN "
    "KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE)",
    "CREATE TABLE matches   (pair_id  INTEGER  PRIMARY KEY  NOT NULL,    rows     INTEGER          "
    "     NOT NULL,    cols     INTEGER               NOT NULL,    data     BLOB)",
    "CREATE TABLE two_view_geometries   (pair_id  INTEGER  PRIMARY KEY  NOT NULL,    rows     "
    "INTEGER               NOT NULL,    cols     INTEGER               NOT NULL,    data     BLOB, "
    " "
    "  config   INTEGER               NOT NULL,    F        BLOB,    E        BLOB,    H        "
    "BLOB,    qvec     BLOB,    tvec     BLOB)",
};

// The tables every generation shares from 3.10 on, and the ones that differ. Same tables, columns,
// types, keys and constraints as COLMAP's; the spacing is ours.
const char* kCameras =
    "CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER NOT "
    "NULL, width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, prior_focal_length "
    "INTEGER NOT NULL)";
const char* kImages =
    "CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT NULL "
    "UNIQUE, camera_id INTEGER NOT NULL, CONSTRAINT image_id_check CHECK(image_id >= 0 and "
    "image_id < 2147483647), FOREIGN KEY(camera_id) REFERENCES cameras(camera_id))";
const char* kImageNameIndex = "CREATE UNIQUE INDEX index_name ON images(name)";
const char* kKeypoints =
    "CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols "
    "INTEGER NOT NULL, data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE "
    "CASCADE)";
const char* kMatches =
    "CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols "
    "INTEGER NOT NULL, data BLOB)";
const char* kTwoViewGeometries =
    "CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT "
    "NULL, cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec "
    "BLOB, tvec BLOB)";

const std::vector<std::string> kSchema310 = {
    kCameras,
    kImages,
    kImageNameIndex,
    "CREATE TABLE pose_priors (image_id INTEGER PRIMARY KEY NOT NULL, position BLOB, "
    "coordinate_system INTEGER NOT NULL, position_covariance BLOB, FOREIGN KEY(image_id) "
    "REFERENCES images(image_id) ON DELETE CASCADE)",
    kKeypoints,
    "CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols "
    "INTEGER NOT NULL, data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE "
    "CASCADE)",
    kMatches,
    kTwoViewGeometries,
};

const std::vector<std::string> kSchema4 = {
    "CREATE TABLE rigs (rig_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, ref_sensor_id INTEGER "
    "NOT NULL, ref_sensor_type INTEGER NOT NULL)",
    "CREATE UNIQUE INDEX rig_ref_sensor_assignment ON rigs(ref_sensor_id, ref_sensor_type)",
    "CREATE TABLE rig_sensors (rig_id INTEGER NOT NULL, sensor_id INTEGER NOT NULL, sensor_type "
    "INTEGER NOT NULL, sensor_from_rig BLOB, FOREIGN KEY(rig_id) REFERENCES rigs(rig_id) ON "
    "DELETE CASCADE)",
    "CREATE UNIQUE INDEX rig_sensor_assignment ON rig_sensors(sensor_id, sensor_type)",
    kCameras,
    "CREATE TABLE frames (frame_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, rig_id INTEGER NOT "
    "NULL, FOREIGN KEY(rig_id) REFERENCES rigs(rig_id) ON DELETE CASCADE)",
    "CREATE TABLE frame_data (frame_id INTEGER NOT NULL, data_id INTEGER NOT NULL, sensor_id "
    "INTEGER NOT NULL, sensor_type INTEGER NOT NULL, FOREIGN KEY(frame_id) REFERENCES "
    "frames(frame_id) ON DELETE CASCADE)",
    "CREATE UNIQUE INDEX frame_sensor_assignment ON frame_data(data_id, sensor_type)",
    kImages,
    kImageNameIndex,
    "CREATE TABLE pose_priors (pose_prior_id INTEGER PRIMARY KEY NOT NULL, corr_data_id INTEGER "
    "NOT NULL, corr_sensor_id INTEGER NOT NULL, corr_sensor_type INTEGER NOT NULL, position BLOB, "
    "position_covariance BLOB, gravity BLOB, coordinate_system INTEGER NOT NULL)",
    "CREATE UNIQUE INDEX pose_prior_data_assignment ON pose_priors(corr_data_id, corr_sensor_id, "
    "corr_sensor_type)",
    kKeypoints,
    "CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, type INTEGER NOT NULL, rows "
    "INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB, FOREIGN KEY(image_id) REFERENCES "
    "images(image_id) ON DELETE CASCADE)",
    kMatches,
    kTwoViewGeometries,
};

bool HasAll(const std::set<std::string>& present, const std::vector<std::string>& columns,
            std::string* missing) {
  for (const std::string& column : columns) {
    if (present.count(column) == 0) {
      *missing = column;
      return false;
    }
  }
  return true;
}

// The pose_priors table's form, from its key column.
void DetectPosePriorTable(sqlite::Connection& db, DatabaseLayout* layout) {
  const std::set<std::string> columns = TableColumns(db, "pose_priors");
  if (columns.empty()) return;
  std::string missing;
  if (columns.count("corr_data_id") != 0) {
    if (!HasAll(columns,
                {"pose_prior_id", "corr_data_id", "corr_sensor_id", "corr_sensor_type", "position",
                 "coordinate_system"},
                &missing)) {
      throw InputError(db.source(), "table 'pose_priors': missing column '" + missing +
                                        "' (COLMAP 4 keys priors by sensor data)");
    }
    layout->pose_priors = PosePriorTable::kBySensorData;
  } else if (columns.count("image_id") != 0) {
    if (!HasAll(columns, {"image_id", "position", "coordinate_system"}, &missing)) {
      throw InputError(db.source(), "table 'pose_priors': missing column '" + missing +
                                        "' (COLMAP 3.10-3.11 key priors by image)");
    }
    layout->pose_priors = PosePriorTable::kByImage;
  } else {
    throw InputError(db.source(),
                     "table 'pose_priors': missing column 'corr_data_id' (COLMAP 4) or "
                     "'image_id' (COLMAP 3.10-3.11): a layout ramap does not know");
  }
  layout->pose_prior_covariance = columns.count("position_covariance") != 0;
  layout->pose_prior_gravity = columns.count("gravity") != 0;
}

// Rigs and frames come as four tables; some but not all of them is a damaged database.
void DetectRigsAndFrames(sqlite::Connection& db, DatabaseLayout* layout) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> tables = {
      {"rigs", {"rig_id", "ref_sensor_id", "ref_sensor_type"}},
      {"rig_sensors", {"rig_id", "sensor_id", "sensor_type", "sensor_from_rig"}},
      {"frames", {"frame_id", "rig_id"}},
      {"frame_data", {"frame_id", "data_id", "sensor_id", "sensor_type"}},
  };
  std::string present_table, missing_table;
  for (const auto& [table, columns] : tables) {
    const std::set<std::string> present = TableColumns(db, table);
    if (present.empty()) {
      missing_table = table;
      continue;
    }
    present_table = table;
    std::string missing;
    if (!HasAll(present, columns, &missing)) {
      throw InputError(db.source(), "table '" + table + "': missing column '" + missing +
                                        "' (COLMAP 3.12-4.x layout)");
    }
  }
  if (present_table.empty()) return;
  if (!missing_table.empty()) {
    throw InputError(db.source(), "missing table '" + missing_table + "' beside table '" +
                                      present_table +
                                      "' (COLMAP 3.12-4.x databases hold rigs, rig_sensors, "
                                      "frames and frame_data)");
  }
  layout->rigs_and_frames = true;
}

}  // namespace

namespace {

// What sets each generation apart when it is named or written.
struct GenerationInfo {
  DatabaseGeneration generation;
  const char* name;   // as --Database.generation takes it
  const char* label;  // for logs and summaries
  int user_version;   // what COLMAP 3.8, 3.11 and 4.1.1 stamp
  const std::vector<std::string>* schema;
};

const GenerationInfo& Info(DatabaseGeneration generation) {
  static const GenerationInfo kInfo[] = {
      {DatabaseGeneration::kColmap38, "3.8", "COLMAP 3.8-3.9", 3800, &kSchema38},
      {DatabaseGeneration::kColmap310, "3.10", "COLMAP 3.10-3.11", 3110000, &kSchema310},
      {DatabaseGeneration::kColmap4, "4", "COLMAP 3.12-4.x", 4010100, &kSchema4},
  };
  for (const GenerationInfo& info : kInfo) {
    if (info.generation == generation) return info;
  }
  return kInfo[0];
}

}  // namespace

std::string DatabaseGenerationName(DatabaseGeneration generation) { return Info(generation).name; }

DatabaseGeneration DatabaseGenerationFromName(const std::string& name, const std::string& option) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (lower == "3.8" || lower == "3.9") return DatabaseGeneration::kColmap38;
  if (lower == "3.10" || lower == "3.11") return DatabaseGeneration::kColmap310;
  if (lower == "4" || lower == "4.x" || lower == "3.12" || lower == "3.13" ||
      lower.rfind("4.", 0) == 0) {
    return DatabaseGeneration::kColmap4;
  }
  throw InputError(option, "'" + name +
                               "' is not a database generation ramap writes: 3.8 (COLMAP 3.8-3.9, "
                               "read by every COLMAP), 3.10 (3.10-3.11) or 4 (3.12-4.x)");
}

std::string DatabaseGenerationLabel(DatabaseGeneration generation) {
  return Info(generation).label;
}

std::set<std::string> TableColumns(sqlite::Connection& db, const std::string& table) {
  sqlite::Statement info(db, "SELECT name FROM pragma_table_info(?)");
  info.BindText(1, table);
  std::set<std::string> columns;
  while (info.Step()) columns.insert(info.ColumnText(0));
  return columns;
}

DatabaseLayout DetectDatabaseLayout(sqlite::Connection& db) {
  DatabaseLayout layout;
  {
    sqlite::Statement version(db, "PRAGMA user_version");
    if (version.Step()) layout.user_version = static_cast<int>(version.ColumnInt64(0));
  }
  if (TableColumns(db, "cameras").empty()) {
    throw InputError(db.source(), "missing table 'cameras' (not a COLMAP database?)");
  }
  const std::set<std::string> image_columns = TableColumns(db, "images");
  if (image_columns.empty()) {
    throw InputError(db.source(), "missing table 'images' (not a COLMAP database?)");
  }
  std::string missing;
  layout.image_prior_columns =
      HasAll(image_columns,
             {"prior_qw", "prior_qx", "prior_qy", "prior_qz", "prior_tx", "prior_ty", "prior_tz"},
             &missing);
  DetectPosePriorTable(db, &layout);
  DetectRigsAndFrames(db, &layout);
  if (layout.rigs_and_frames) {
    layout.generation = DatabaseGeneration::kColmap4;
  } else if (layout.pose_priors != PosePriorTable::kNone) {
    layout.generation = DatabaseGeneration::kColmap310;
  } else if (layout.image_prior_columns) {
    layout.generation = DatabaseGeneration::kColmap38;
  } else {
    throw InputError(db.source(),
                     "table 'images': missing column '" + missing +
                         "' (COLMAP 3.8-3.9), and no table 'pose_priors' (COLMAP 3.10-3.11) or "
                         "'frames' (COLMAP 3.12-4.x): not a COLMAP database of a generation "
                         "ramap knows");
  }
  return layout;
}

const std::vector<std::string>& SchemaStatements(DatabaseGeneration generation) {
  return *Info(generation).schema;
}

int SchemaUserVersion(DatabaseGeneration generation) { return Info(generation).user_version; }

}  // namespace ramap
