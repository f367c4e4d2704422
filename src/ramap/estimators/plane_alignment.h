// A model set upright on its dominant plane, as COLMAP's `model_aligner --alignment_type plane`
// (3D Gaussian Splatting's convert.py runs it so that +Z is up).
#pragma once

#include <string>

#include "ramap/geometry/alignment.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// The rigid motion (scale 1) that moves the centroid of the 3D points to the origin and their
// principal plane (the two directions of largest spread, by principal component analysis) to
// z = 0, with the first registered camera on the +Z side. Throws InputError naming `source` when
// the model has fewer than three 3D points or no registered image.
Sim3d PrincipalPlaneAlignment(const Reconstruction& model, const std::string& source);

}  // namespace ramap
