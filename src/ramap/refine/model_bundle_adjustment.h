// Bundle adjustment of a model on its own, as COLMAP's `bundle_adjuster` does it: no database, the
// model's observations are the measurements. nerfstudio runs it after the mapper to refine the
// principal point.
#pragma once

#include <string>

#include "ramap/refine/bundle_adjustment.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// Refines `model` in place (poses, points, and the intrinsics `options` ask for), every point
// whatever options.max_num_points says. Observations are the model's points2D, undistorted
// through its cameras. Throws InputError naming `source` when a camera's parameters are unusable
// or the model has no observation.
BundleAdjustmentSummary BundleAdjustModel(Reconstruction* model,
                                          const BundleAdjustmentOptions& options,
                                          const std::string& source);

}  // namespace ramap
