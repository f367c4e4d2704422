// The parts of a COLMAP database that changed between generations (io/colmap_database_schema.h):
// pose priors and, from 3.12 on, rigs and frames. Helpers of io/colmap_database.h, which reads
// and writes the rest.
#pragma once

#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/sqlite.h"
#include "ramap/scene/features.h"

namespace ramap {

// Reads the pose_priors table of either form into database->images (after the images are read):
// position, coordinate system, covariance and gravity; NULL or NaN values are left empty. A prior
// there replaces one from the old prior_t* columns (COLMAP 4 reads only the table). Throws
// InputError naming the database and the prior: an unknown coordinate system, a blob of the wrong
// size, a prior for an image or sensor that is not in the database.
void ReadDatabasePosePriors(sqlite::Connection& db, const DatabaseLayout& layout,
                            FeatureDatabase* database);

// Reads rigs, rig_sensors, frames and frame_data into database->rigs and frames (after cameras and
// images). Throws InputError naming the rig or frame when a sensor is missing: a rig whose camera
// is not in table cameras, a frame whose rig is unknown or whose datum comes from a sensor that is
// not in its rig, an image that is not in table images or was taken by another camera.
void ReadDatabaseRigsAndFrames(sqlite::Connection& db, FeatureDatabase* database);

// The rigs and frames to store: the database's own, else one rig per camera (rig id = camera id)
// and one frame per image (frame id = image id), as COLMAP 4 makes for a database without them.
Rigs RigsOrOnePerCamera(const FeatureDatabase& database);
Frames FramesOrOnePerImage(const FeatureDatabase& database);

// What a database's rigs and frames hold, for logs and summaries: multi-camera frames are read,
// but each of their images is still averaged on its own.
struct RigSummary {
  size_t num_rigs = 0;
  size_t num_frames = 0;
  size_t num_multi_camera_frames = 0;  // frames holding images of two or more cameras
  size_t max_cameras_per_frame = 0;
};
RigSummary SummarizeRigs(const FeatureDatabase& database);

// Inserts the pose priors of database->images into a new database of `generation` (3.10: by image;
// 4: by sensor data; 3.8 keeps them in the images table, written with the images).
void WriteDatabasePosePriors(const FeatureDatabase& database, DatabaseGeneration generation,
                             sqlite::Connection& db);

// Inserts RigsOrOnePerCamera and FramesOrOnePerImage into a new 3.12-4.x database.
void WriteDatabaseRigsAndFrames(const FeatureDatabase& database, sqlite::Connection& db);

}  // namespace ramap
