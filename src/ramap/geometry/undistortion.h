// The ideal pinhole camera of a distorted one, for the tools that need undistorted images and
// PINHOLE cameras (3D Gaussian Splatting, gsplat, MVS): COLMAP's `image_undistorter` camera.
//
// The focal lengths are kept; the image size (and with it the principal point) is scaled so that
// the undistorted image holds all of the distorted image's pixels (blank_pixels = 1), none of the
// pixels outside it (blank_pixels = 0, COLMAP's default), or in between; the scale is clamped to
// [min_scale, max_scale], then the whole camera is scaled down to max_image_size. These are the
// semantics of COLMAP's image_undistorter options (src/colmap/image/undistortion.h), so that a
// tool that passes them gets the images it expects.
#pragma once

#include <Eigen/Core>

#include "ramap/scene/camera.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct UndistortionOptions {
  // Share of blank (black) pixels allowed at the borders, 0-1 (COLMAP's --blank_pixels, default 0).
  double blank_pixels = 0.0;
  // Bounds of the image-size scale (COLMAP's --min_scale, --max_scale defaults).
  double min_scale = 0.2;
  double max_scale = 2.0;
  // Longest side of the undistorted images in pixels; <= 0: no limit (COLMAP's --max_image_size,
  // default -1).
  int max_image_size = -1;

  // Throws InputError naming the option.
  void Check() const;
};

// Its options, as `ramap image_undistorter` takes them (COLMAP's names: --blank_pixels, ...),
// each declared once with its range and help (util/option_table.h).
const OptionTable<UndistortionOptions>& UndistortionOptionTable();

// The PINHOLE camera (same id) of `camera`. Throws InputError (naming `source`) for a camera whose
// borders cannot be undistorted (a fisheye wider than a pinhole image can show).
Camera UndistortedCamera(const Camera& camera, const UndistortionOptions& options,
                         const std::string& source);

// The pixel of `undistorted` that sees what `pixel` of `distorted` sees; NaN where it has none.
Eigen::Vector2d UndistortPixel(const Camera& distorted, const Camera& undistorted,
                               const Eigen::Vector2d& pixel);

}  // namespace ramap
