// The triangulation stage: with every pose fixed, the feature tracks are triangulated and the
// result is assembled as a COLMAP model (cameras, registered images with their keypoints, 3D
// points).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/geometry/triangulation.h"
#include "ramap/graph/tracks.h"
#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct TrackTriangulationOptions {
  // COLMAP's mapper filters observations above 4 px (Mapper.filter_max_reproj_error).
  double max_reprojection_error_px = 4.0;
  // COLMAP's Mapper.filter_min_tri_angle.
  double min_triangulation_angle_deg = 1.5;
  // Where the points start bundle adjustment, observations are kept up to this angle from their
  // point instead (0: max_reprojection_error_px there too). Averaging's poses are a few tenths of a
  // degree off, so 4 px judged against them detaches observations that BA would fit, and the
  // start's points then decide BA's basin without them (sceaux_castle given as PINHOLE). BA's
  // robust loss weighs the far ones and its max_reprojection_error_px detaches what still lies off
  // after it. GLOMAP keeps its tracks up to 1 deg before its BA
  // (GlobalMapper.max_angular_reproj_error_deg).
  double start_max_error_deg = 1.0;
  // The bound in use as an angle, 0: max_reprojection_error_px. Set by ForBundleAdjustmentStart,
  // not an option.
  double max_error_deg = 0.0;

  void Check() const;
  // These options where the points start bundle adjustment (start_max_error_deg).
  TrackTriangulationOptions ForBundleAdjustmentStart() const;
};

// Its options (--Triangulation.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<TrackTriangulationOptions>& TrackTriangulationOptionTable();

struct TrackTriangulationSummary {
  int num_tracks = 0;
  int num_points = 0;
  int num_observations = 0;
  int num_rejected_tracks = 0;  // too few agreeing rays, too small an angle, or behind a camera
  double mean_reprojection_error_px = 0.0;
};

// A model of the images in `poses` (cam_from_world): their cameras, keypoints as points2D, and one
// 3D point per track that triangulates. `bearings` holds each image's undistorted unit bearings
// (indexed like its keypoints) and `focal_lengths_px` each camera's mean focal length, which turns
// the pixel bound into an angle. Reprojection errors are measured on the normalised plane scaled by
// the focal length (exact for undistorted pinhole cameras). Tracks are triangulated on
// `num_threads` threads; the model is the same for any number.
Reconstruction BuildReconstruction(
    const FeatureDatabase& database, const std::map<uint32_t, Rigid3d>& poses,
    const std::vector<Track>& tracks, const KeypointBearings& bearings,
    const std::map<uint32_t, double>& focal_lengths_px,
    const TrackTriangulationOptions& options = TrackTriangulationOptions(),
    TrackTriangulationSummary* summary = nullptr, int num_threads = 1);

}  // namespace ramap
