// Reading and writing COLMAP 3.8 databases (SQLite): cameras, images, keypoints, descriptors,
// matches and two_view_geometries.
//
// The reader checks the schema with PRAGMA table_info before reading, so a database of another
// layout gets a message naming the missing table or column instead of a crash. Every defect
// (truncated blob, keypoint index out of range, unknown camera model, NaN intrinsics, ...) throws
// InputError naming the database file and the item.
#pragma once

#include <string>

#include "ramap/scene/features.h"

namespace ramap {

struct DatabaseReadOptions {
  // Descriptors are only needed to match again; skipping them makes large databases fast to read.
  bool read_descriptors = false;
  // Raw (unverified) matches; the mapper needs only two_view_geometries.
  bool read_matches = true;
};

FeatureDatabase ReadColmapDatabase(const std::string& path,
                                   const DatabaseReadOptions& options = DatabaseReadOptions());

// Writes a new database with COLMAP 3.8's schema at `path` (replacing any file there), staged
// under a temporary name and renamed when complete. Geometries are held with image_id1 <
// image_id2 in `database`; the writer checks that.
void WriteColmapDatabase(const FeatureDatabase& database, const std::string& path);

}  // namespace ramap
