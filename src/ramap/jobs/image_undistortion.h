// COLMAP's `image_undistorter --output_type COLMAP`: a model's images undistorted to its cameras'
// ideal pinhole versions (geometry/undistortion.h), in the layout 3D Gaussian Splatting, gsplat
// and nerfstudio read: OUTPUT/images/NAME and OUTPUT/sparse/{cameras,images,points3D,rigs,frames}.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "ramap/geometry/undistortion.h"
#include "ramap/io/colmap_model.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// `model` seen through undistorted cameras: PINHOLE cameras of the same ids, each observation
// moved to the pixel that sees the same ray. An observation whose ray the pinhole image cannot
// show is detached from its 3D point (and the point removed when fewer than two observations
// remain). Throws InputError (naming `source`) as UndistortedCamera.
Reconstruction UndistortReconstruction(const Reconstruction& model,
                                       const UndistortionOptions& options,
                                       const std::string& source);

struct ImageUndistortionSummary {
  int num_images = 0;
  double seconds = 0.0;
};

// Writes every registered image of `model`, read as image_path/NAME, undistorted (bilinear, black
// outside the distorted image) to output_path/images/NAME in its own format, and the undistorted
// model to output_path/sparse. Each file is staged and renamed into place; files already there
// under those names are replaced, nothing else is touched. Throws InputError when output_path's
// images folder is image_path itself (the originals would be overwritten), an image is missing,
// unreadable or not of its camera's size, or a file cannot be written: then nothing appears.
ImageUndistortionSummary UndistortImages(const Reconstruction& model, const std::string& image_path,
                                         const std::string& output_path,
                                         const UndistortionOptions& options, ModelFormat format,
                                         int num_threads, std::ostream* progress);

}  // namespace ramap
