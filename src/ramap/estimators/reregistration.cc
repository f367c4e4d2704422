#include "ramap/estimators/reregistration.h"

#include <cmath>
#include <set>

#include "ramap/estimators/track_triangulation.h"
#include "ramap/geometry/absolute_pose.h"
#include "ramap/util/option_check.h"
#include "ramap/util/statistics.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

// One image's keypoints on tracks with a point: their bearings, the points, and how many the
// point's own track holds (observations with the current pose).
struct Correspondences {
  std::vector<Eigen::Vector3d> bearings;
  std::vector<Eigen::Vector3d> points;
  int num_observed = 0;
  int num_correspondences = 0;  // bearings.size() once gathered
};

// For each image, the track each of its keypoints is on (-1: none), indexed by keypoint: a flat
// table rather than a map of (image, keypoint) pairs, which took most of this stage's time.
std::map<uint32_t, std::vector<int>> TrackOfKeypoint(const std::vector<Track>& tracks,
                                                     const KeypointBearings& bearings) {
  std::map<uint32_t, std::vector<int>> track_of;
  for (const auto& [image_id, image_bearings] : bearings)
    track_of[image_id].assign(image_bearings.size(), -1);
  for (size_t k = 0; k < tracks.size(); ++k) {
    for (const TrackElement& e : tracks[k]) {
      const auto image = track_of.find(e.image_id);
      if (image != track_of.end() && e.point2D_idx < image->second.size())
        image->second[e.point2D_idx] = static_cast<int>(k);
    }
  }
  return track_of;
}

// For each image, its keypoints whose track triangulated, whether or not the point kept them: the
// counts for every image, the bearings and points only for those `gather` accepts. `track_of` is
// TrackOfKeypoint's table.
template <typename Gather>
std::map<uint32_t, Correspondences> CorrespondencesByImage(
    const std::vector<Track>& tracks, const std::map<uint32_t, std::vector<int>>& track_of,
    const KeypointBearings& bearings, const Reconstruction& reconstruction, const Gather& gather) {
  std::map<uint32_t, Correspondences> by_image;
  for (const auto& [point3D_id, point] : reconstruction.points3D) {
    // A point's track holds some elements of the track it came from: any one finds it.
    const TrackElement& first = point.track.front();
    const auto image_tracks = track_of.find(first.image_id);
    if (image_tracks == track_of.end() || first.point2D_idx >= image_tracks->second.size() ||
        image_tracks->second[first.point2D_idx] < 0) {
      continue;
    }
    for (const TrackElement& e : tracks[image_tracks->second[first.point2D_idx]]) {
      const auto image = reconstruction.images.find(e.image_id);
      const auto image_bearings = bearings.find(e.image_id);
      if (image == reconstruction.images.end() || image_bearings == bearings.end() ||
          e.point2D_idx >= image_bearings->second.size() ||
          e.point2D_idx >= image->second.points2D.size()) {
        continue;
      }
      Correspondences& c = by_image[e.image_id];
      ++c.num_correspondences;
      c.num_observed += image->second.points2D[e.point2D_idx].point3D_id == point3D_id;
      if (!gather(e.image_id)) continue;
      c.bearings.push_back(image_bearings->second[e.point2D_idx]);
      c.points.push_back(point.xyz);
    }
  }
  return by_image;
}

// The median over the images of the fraction of their keypoints on triangulated tracks that are
// observations of their points.
double MedianObservedRatio(const std::map<uint32_t, Correspondences>& by_image) {
  std::vector<double> ratios;
  for (const auto& [image_id, c] : by_image) {
    if (c.num_correspondences > 0)
      ratios.push_back(static_cast<double>(c.num_observed) / c.num_correspondences);
  }
  return ratios.empty() ? 0.0 : Median(std::move(ratios));
}

double RotationChangeDeg(const Rigid3d& a, const Rigid3d& b) {
  return a.rotation.angularDistance(b.rotation) * 180.0 / M_PI;
}

}  // namespace

void ReregistrationOptions::Check() const { CheckOptionValues(ReregistrationOptionTable(), *this); }

std::vector<ReregisteredImage> ReregisterImages(const std::vector<Track>& tracks,
                                                const KeypointBearings& bearings,
                                                const std::map<uint32_t, double>& focal_lengths_px,
                                                const Reconstruction& reconstruction,
                                                const ReregistrationOptions& options,
                                                double max_reprojection_error_px,
                                                std::map<uint32_t, Rigid3d>* poses) {
  options.Check();
  std::vector<ReregisteredImage> tried;
  if (!options.enable) return tried;
  // Counted for every image first; the bearings and points gathered for the images tried alone
  // (usually none).
  const std::map<uint32_t, std::vector<int>> track_of = TrackOfKeypoint(tracks, bearings);
  const std::map<uint32_t, Correspondences> counts = CorrespondencesByImage(
      tracks, track_of, bearings, reconstruction, [](uint32_t) { return false; });
  const double max_observed_ratio = options.max_inlier_ratio * MedianObservedRatio(counts);
  const auto left_out = [&](const Correspondences& c) {
    return c.num_correspondences >= options.min_num_correspondences &&
           c.num_observed < max_observed_ratio * c.num_correspondences;
  };
  std::set<uint32_t> candidates;
  for (const auto& [image_id, c] : counts)
    if (left_out(c)) candidates.insert(image_id);
  if (candidates.empty()) return tried;
  const std::map<uint32_t, Correspondences> by_image =
      CorrespondencesByImage(tracks, track_of, bearings, reconstruction,
                             [&](uint32_t id) { return candidates.count(id) > 0; });
  for (const uint32_t image_id : candidates) {
    const Correspondences& c = by_image.at(image_id);
    const int num_correspondences = c.num_correspondences;
    const Image& image = reconstruction.images.at(image_id);
    ReregisteredImage result;
    result.image_id = image_id;
    result.name = image.name;
    result.num_correspondences = num_correspondences;
    AbsolutePoseOptions absolute;
    absolute.max_angular_error_rad =
        max_reprojection_error_px / focal_lengths_px.at(image.camera_id);
    absolute.min_num_inliers = options.min_num_correspondences;
    // Counted as the new pose's are, so that the two compare.
    result.num_inliers_before =
        static_cast<int>(AbsolutePoseInliers(image.cam_from_world, c.bearings, c.points,
                                             absolute.max_angular_error_rad)
                             .size());
    if (const std::optional<AbsolutePose> pose =
            EstimateAbsolutePose(c.bearings, c.points, absolute)) {
      result.num_inliers_after = static_cast<int>(pose->inliers.size());
      result.rotation_change_deg = RotationChangeDeg(image.cam_from_world, pose->cam_from_world);
      result.replaced =
          result.num_inliers_after >= options.min_inlier_gain * result.num_inliers_before;
      if (result.replaced) (*poses)[image_id] = pose->cam_from_world;
    }
    tried.push_back(result);
  }
  return tried;
}

}  // namespace ramap
