// Reading and writing COLMAP databases (SQLite) of every generation, 3.8 to 4.x
// (io/colmap_database_schema.h): cameras, images, pose priors, rigs and frames, keypoints,
// descriptors, matches and two_view_geometries.
//
// The reader checks the schema with PRAGMA table_info before reading, so a database of another
// layout gets a message naming the missing table or column instead of a crash. Every defect
// (truncated blob, keypoint index out of range, unknown camera model, NaN intrinsics, ...) throws
// InputError naming the database file and the item. The reader never writes to the file.
//
// Layout, as every generation stores it: camera params float64; keypoints float32 rows x {2, 4, 6};
// descriptors uint8 rows x cols; matches uint32 rows x 2 with pair_id = i * 2147483647 + j, i < j,
// and the first column indexing image i; two-view F, E, H float64 3x3 ROW-major; qvec (w, x, y, z)
// and tvec float64, the pose cam2_from_cam1 of the pair (camera 2 being image j); 4.x stores an
// unknown F, E, H or pose as NULL, older versions as zeros and the identity.
//
// One table is ramap's own: ramap_match_confidence(pair_id, rows, data), the float32 descriptor
// ratio of each inlier match of a pair's two-view geometry (TwoViewGeometry::inlier_ratios). It is
// written only when some geometry has ratios, so a database without them has exactly COLMAP's
// schema; COLMAP's reader and mapper ignore tables they do not know.
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

// What the mapper's stages read: keypoints and two-view geometries, not the raw matches (which on
// a long drive are as large as everything else together).
inline DatabaseReadOptions MapperDatabaseReadOptions() {
  DatabaseReadOptions options;
  options.read_matches = false;
  return options;
}

// Reads everything `options` asks for. Values the database leaves empty read as: NULL or NaN
// image priors -> empty optionals; NULL or empty F/E/H -> zero matrices (old databases); NULL,
// empty or zero qvec -> identity rotation; NULL or empty tvec -> zero translation.
FeatureDatabase ReadColmapDatabase(const std::string& path,
                                   const DatabaseReadOptions& options = DatabaseReadOptions());

// The generation of the database at `path` (its tables only; no row is read). Throws InputError
// as ReadColmapDatabase for a file that is no COLMAP database.
DatabaseGeneration ReadDatabaseGeneration(const std::string& path);

// The names of the database's images, sorted (read without matches or descriptors).
std::vector<std::string> ReadDatabaseImageNames(const std::string& path);

// Writes a new database of `generation` at `path` (replacing any file there), staged under a
// temporary name and renamed when complete, in one transaction. 3.8 (the default) is COLMAP 3.8's
// exact schema, which every COLMAP from 3.8 to 4.x reads (4.x upgrades it when it opens it);
// 3.10 and 4 are the layouts of COLMAP 3.11 and 4.1.1. In a 4.x database the pose priors keep no
// rotation (its pose_priors table has none), and images without rigs and frames get one rig per
// camera and one frame per image.
//
// Geometries are stored with image_id1 < image_id2. A geometry given the other way round (its
// image_id1 > image_id2, under the key of its pair) is inverted with InvertTwoViewGeometry before
// storing, as COLMAP's own writer does. Raw matches are taken as already in database order.
// The contents are checked first (ids consistent, parameter counts, finite intrinsics, keypoint
// indices in range) so that everything written reads back; a defect throws InputError naming
// `path` and the item, and nothing is written.
void WriteColmapDatabase(const FeatureDatabase& database, const std::string& path,
                         DatabaseGeneration generation = DatabaseGeneration::kColmap38);

// Replaces, in place and in one transaction, the matches, two-view geometries and ramap's
// descriptor ratios of the existing database at `path` by those of `database`, whose images must
// be the file's own (same ids and names). Every other table and row, including tables ramap does
// not know, is kept; on any failure the file is left as it was. The file keeps its generation.
void WriteColmapDatabaseMatches(const FeatureDatabase& database, const std::string& path);

// What `ramap database_info` reports: the counts of each kind of row.
struct DatabaseCounts {
  size_t num_keypoints = 0;
  size_t num_descriptors = 0;
  size_t num_pairs_with_matches = 0;
  size_t num_matches = 0;
  size_t num_verified_pairs = 0;  // two-view geometries with inlier matches
  size_t num_inliers = 0;
  std::map<TwoViewConfig, size_t> verified_pairs_by_config;
  size_t num_pose_priors = 0;
  size_t num_rotation_priors = 0;
  size_t num_pairs_with_ratios = 0;  // ramap's ramap_match_confidence table
};
DatabaseCounts CountDatabase(const FeatureDatabase& database);

}  // namespace ramap
