#include "ramap/estimators/track_triangulation.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/timer.h"

namespace ramap {

void TrackTriangulationOptions::Check() const {
  CheckOptionValues(TrackTriangulationOptionTable(), *this);
  CheckOption(max_error_deg >= 0 && max_error_deg < 90, "TrackTriangulationOptions::max_error_deg",
              "in [0, 90)", max_error_deg);
}

TrackTriangulationOptions TrackTriangulationOptions::ForBundleAdjustmentStart() const {
  TrackTriangulationOptions start = *this;
  start.max_error_deg = start_max_error_deg;
  return start;
}

namespace {

// The rays of a track from the posed images that have its keypoint, the elements they come from,
// and the mean focal length of their cameras.
struct TrackRays {
  std::vector<RayObservation> rays;
  std::vector<const TrackElement*> elements;
  double focal_px = 0.0;
};

TrackRays RaysOfTrack(const Track& track, const FeatureDatabase& database,
                      const std::map<uint32_t, Rigid3d>& poses, const KeypointBearings& bearings,
                      const std::map<uint32_t, double>& focal_lengths_px,
                      const Reconstruction& reconstruction) {
  TrackRays result;
  double focal_sum = 0.0;
  for (const TrackElement& element : track) {
    const auto pose = poses.find(element.image_id);
    const auto image_bearings = bearings.find(element.image_id);
    if (pose == poses.end() || image_bearings == bearings.end() ||
        element.point2D_idx >= image_bearings->second.size() ||
        element.point2D_idx >= reconstruction.images.at(element.image_id).points2D.size()) {
      continue;
    }
    result.rays.push_back({pose->second, image_bearings->second[element.point2D_idx]});
    result.elements.push_back(&element);
    focal_sum += focal_lengths_px.at(database.images.at(element.image_id).camera_id);
  }
  if (!result.rays.empty()) result.focal_px = focal_sum / result.rays.size();
  return result;
}

// A track's point (its inlier observations as its track, their mean reprojection error) before it
// is numbered.
struct TriangulatedTrack {
  bool seen_twice = false;       // by at least two posed images
  std::optional<Point3D> point;  // empty when the rays do not agree on one
  double error_sum_px = 0.0;     // over the point's observations
};

TriangulatedTrack TriangulateTrack(const Track& track, const FeatureDatabase& database,
                                   const std::map<uint32_t, Rigid3d>& poses,
                                   const KeypointBearings& bearings,
                                   const std::map<uint32_t, double>& focal_lengths_px,
                                   const Reconstruction& reconstruction,
                                   const TrackTriangulationOptions& options) {
  TriangulatedTrack result;
  const TrackRays rays =
      RaysOfTrack(track, database, poses, bearings, focal_lengths_px, reconstruction);
  if (rays.rays.size() < 2) return result;
  result.seen_twice = true;
  TriangulationOptions triangulation;
  triangulation.max_angular_error_rad = options.max_error_deg > 0
                                            ? options.max_error_deg * M_PI / 180.0
                                            : options.max_reprojection_error_px / rays.focal_px;
  triangulation.min_triangulation_angle_deg = options.min_triangulation_angle_deg;
  const std::optional<TriangulatedPoint> triangulated = TriangulatePoint(rays.rays, triangulation);
  if (!triangulated) return result;
  Point3D point;
  point.xyz = triangulated->xyz;
  for (const int i : triangulated->inliers) {
    const TrackElement& element = *rays.elements[i];
    const Eigen::Vector3d x = rays.rays[i].cam_from_world * point.xyz;
    const Eigen::Vector3d& f = rays.rays[i].bearing;
    const double focal = focal_lengths_px.at(database.images.at(element.image_id).camera_id);
    result.error_sum_px += f.z() > 0 ? focal * (x.head<2>() / x.z() - f.head<2>() / f.z()).norm()
                                     : focal * std::atan2(x.cross(f).norm(), x.dot(f));
    point.track.push_back(element);
  }
  point.error = result.error_sum_px / point.track.size();
  // Rays that agree only at infinity (cameras that share a centre, a pose placed by rotation
  // alone) can give a point or an error that is not finite: no point, rather than one no
  // reader accepts.
  if (!point.xyz.allFinite() || !std::isfinite(point.error)) {
    result.error_sum_px = 0.0;
    return result;
  }
  result.point = std::move(point);
  return result;
}

}  // namespace

Reconstruction BuildReconstruction(const FeatureDatabase& database,
                                   const std::map<uint32_t, Rigid3d>& poses,
                                   const std::vector<Track>& tracks,
                                   const KeypointBearings& bearings,
                                   const std::map<uint32_t, double>& focal_lengths_px,
                                   const TrackTriangulationOptions& options,
                                   TrackTriangulationSummary* summary, int num_threads) {
  options.Check();
  Reconstruction reconstruction;
  for (const auto& [image_id, pose] : poses) {
    const Image& source = database.images.at(image_id);
    Image image = source;
    image.cam_from_world = pose;
    image.points2D.clear();
    if (const auto keypoints = database.keypoints.find(image_id);
        keypoints != database.keypoints.end()) {
      image.points2D.resize(keypoints->second.size());
      for (size_t k = 0; k < keypoints->second.size(); ++k)
        image.points2D[k].xy = keypoints->second.xy(k);
    }
    reconstruction.cameras[image.camera_id] = database.cameras.at(image.camera_id);
    reconstruction.images[image_id] = std::move(image);
  }

  // Every track is triangulated on the threads, on its own; the points are then numbered in track
  // order, so that the model does not depend on the threads.
  std::vector<TriangulatedTrack> triangulated(tracks.size());
  ParallelFor(tracks.size(), num_threads, [&](size_t k) {
    triangulated[k] = TriangulateTrack(tracks[k], database, poses, bearings, focal_lengths_px,
                                       reconstruction, options);
  });
  TrackTriangulationSummary counts;
  double sum_error_px = 0.0;
  uint64_t next_point3D_id = 1;
  for (TriangulatedTrack& track : triangulated) {
    if (!track.seen_twice) continue;
    ++counts.num_tracks;
    if (!track.point) {
      ++counts.num_rejected_tracks;
      continue;
    }
    const uint64_t point3D_id = next_point3D_id++;
    for (const TrackElement& element : track.point->track) {
      reconstruction.images.at(element.image_id).points2D[element.point2D_idx].point3D_id =
          point3D_id;
    }
    sum_error_px += track.error_sum_px;
    counts.num_observations += static_cast<int>(track.point->track.size());
    reconstruction.points3D[point3D_id] = std::move(*track.point);
  }
  counts.num_points = static_cast<int>(reconstruction.points3D.size());
  counts.mean_reprojection_error_px =
      counts.num_observations ? sum_error_px / counts.num_observations : 0.0;
  if (summary != nullptr) *summary = counts;
  return reconstruction;
}

}  // namespace ramap
