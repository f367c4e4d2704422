// Undistorted unit bearing vectors of every keypoint, computed once per database and shared by the
// relative-pose, translation, triangulation and refinement stages.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "ramap/scene/features.h"

namespace ramap {

struct ImageBearings {
  KeypointBearings bearings;
  // camera id -> mean focal length in pixels (turns pixel thresholds into angles).
  std::map<uint32_t, double> focal_lengths_px;
};

// Throws InputError (naming `source`) when a camera's parameters are unusable.
ImageBearings ComputeBearings(const FeatureDatabase& database, const std::string& source);

// The same through `cameras` (e.g. calibrated or refined intrinsics) instead of the database's,
// for the images in `image_ids` (all the database's images when empty).
ImageBearings ComputeBearings(const FeatureDatabase& database,
                              const std::map<uint32_t, Camera>& cameras, const std::string& source,
                              const std::vector<uint32_t>& image_ids = {});

}  // namespace ramap
