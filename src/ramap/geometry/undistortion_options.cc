#include "ramap/geometry/undistortion.h"

namespace ramap {

const OptionTable<UndistortionOptions>& UndistortionOptionTable() {
  static const OptionTable<UndistortionOptions> table = {
      NumberOption<UndistortionOptions>(
          "blank_pixels", [](auto& o) -> auto& { return o.blank_pixels; }, AtLeast(0, 1),
          "share of blank border pixels allowed, 0 (crop) to 1 (keep every pixel)"),
      NumberOption<UndistortionOptions>(
          "min_scale", [](auto& o) -> auto& { return o.min_scale; }, Above(0),
          "smallest scale of the undistorted image"),
      NumberOption<UndistortionOptions>(
          "max_scale", [](auto& o) -> auto& { return o.max_scale; }, Above(0),
          "largest scale of the undistorted image"),
      NumberOption<UndistortionOptions>(
          "max_image_size", [](auto& o) -> auto& { return o.max_image_size; }, AnyNumber(),
          "longest side of the undistorted images (<= 0: as the images)")};
  return table;
}

}  // namespace ramap
