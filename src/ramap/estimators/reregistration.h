// Images that averaging placed badly, registered again from the points the others triangulate.
// With every pose fixed, a track's point comes from the rays that agree; the rays of an image
// whose pose is wrong do not, so most of its tracks' points leave it out. Such an image's pose is
// estimated again from its bearings to those points (geometry/absolute_pose.h) and replaces the
// averaged one when it explains clearly more of them; the tracks are then triangulated again.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/graph/tracks.h"
#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct ReregistrationOptions {
  bool enable = true;
  // An image is tried when the fraction of its keypoints on triangulated tracks that are
  // observations of their points is below this times the median image's: the others' points
  // leave it out. Where they leave out most images, the intrinsics are far off (a focal length
  // the view graph could not estimate), not the poses, and absolute poses through them place
  // none, so trying them only costs time (a synthetic turntable from 1.6 times its focal length;
  // docs/benchmark-history.md, "Where the seconds of bundle adjustment go")...
  double max_inlier_ratio = 0.5;
  // ...and it has at least this many such keypoints; a new pose needs as many inliers.
  int min_num_correspondences = 30;
  // The new pose replaces the averaged one when it has this many times its inliers.
  double min_inlier_gain = 1.5;

  void Check() const;
};

// Its options (--Reregistration.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<ReregistrationOptions>& ReregistrationOptionTable();

struct ReregisteredImage {
  uint32_t image_id = 0;
  std::string name;
  int num_correspondences = 0;  // keypoints on triangulated tracks
  int num_inliers_before = 0;   // observations of their points with the averaged pose
  int num_inliers_after = 0;    // agreeing with the new pose (0: none found)
  double rotation_change_deg = 0.0;
  bool replaced = false;
};

// Tries every image of `reconstruction` (triangulated from `tracks` with `poses`) that its points
// leave out, and replaces its entry in `poses` when the new pose passes. `bearings` per image,
// `focal_lengths_px` per camera, `max_reprojection_error_px` as triangulation's bound.
std::vector<ReregisteredImage> ReregisterImages(const std::vector<Track>& tracks,
                                                const KeypointBearings& bearings,
                                                const std::map<uint32_t, double>& focal_lengths_px,
                                                const Reconstruction& reconstruction,
                                                const ReregistrationOptions& options,
                                                double max_reprojection_error_px,
                                                std::map<uint32_t, Rigid3d>* poses);

}  // namespace ramap
