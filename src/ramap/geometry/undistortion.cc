#include "ramap/geometry/undistortion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ramap/geometry/camera_projection.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"

namespace ramap {
namespace {

struct PinholeParams {
  double fx, fy, cx, cy;
};

PinholeParams PinholePart(const Camera& camera) {
  const Eigen::Matrix3d K = CalibrationMatrix(camera);
  return {K(0, 0), K(1, 1), K(0, 2), K(1, 2)};
}

Camera MakePinhole(const Camera& camera, const PinholeParams& p, uint64_t width, uint64_t height) {
  Camera pinhole;
  pinhole.camera_id = camera.camera_id;
  pinhole.model = CameraModel::kPinhole;
  pinhole.width = width;
  pinhole.height = height;
  pinhole.params = {p.fx, p.fy, p.cx, p.cy};
  pinhole.has_prior_focal_length = camera.has_prior_focal_length;
  return pinhole;
}

// Where the distorted image's borders land in the pinhole image of the same intrinsics: along
// each border, the smallest and largest coordinate reached.
struct BorderRange {
  double left_min = std::numeric_limits<double>::max(), left_max = -left_min;
  double right_min = left_min, right_max = -left_min;
  double top_min = left_min, top_max = -left_min;
  double bottom_min = left_min, bottom_max = -left_min;
};

void Extend(double value, double* low, double* high) {
  *low = std::min(*low, value);
  *high = std::max(*high, value);
}

BorderRange UndistortedBorders(const Camera& camera, const Camera& pinhole,
                               const std::string& source) {
  BorderRange range;
  const double w = static_cast<double>(camera.width);
  const double h = static_cast<double>(camera.height);
  const auto undistort = [&](double x, double y) {
    const Eigen::Vector2d p = UndistortPixel(camera, pinhole, Eigen::Vector2d(x, y));
    if (!p.allFinite()) {
      throw InputError(source, "camera " + std::to_string(camera.camera_id) + " (" +
                                   CameraModelName(camera.model) +
                                   "): its image border cannot be undistorted to a pinhole image");
    }
    return p;
  };
  for (uint64_t row = 0; row < camera.height; ++row) {
    const double y = row + 0.5;
    Extend(undistort(0.5, y).x(), &range.left_min, &range.left_max);
    Extend(undistort(w - 0.5, y).x(), &range.right_min, &range.right_max);
  }
  for (uint64_t col = 0; col < camera.width; ++col) {
    const double x = col + 0.5;
    Extend(undistort(x, 0.5).y(), &range.top_min, &range.top_max);
    Extend(undistort(x, h - 0.5).y(), &range.bottom_min, &range.bottom_max);
  }
  return range;
}

}  // namespace

void UndistortionOptions::Check() const {
  CheckOptionValues(UndistortionOptionTable(), *this);
  CheckOption(max_scale >= min_scale, "--max_scale", ">= --min_scale", max_scale);
}

Eigen::Vector2d UndistortPixel(const Camera& distorted, const Camera& undistorted,
                               const Eigen::Vector2d& pixel) {
  return ProjectToPixel(undistorted, PixelToBearing(distorted, pixel));
}

Camera UndistortedCamera(const Camera& camera, const UndistortionOptions& options,
                         const std::string& source) {
  PinholeParams p = PinholePart(camera);
  uint64_t width = camera.width;
  uint64_t height = camera.height;
  if (camera.model != CameraModel::kPinhole && camera.model != CameraModel::kSimplePinhole) {
    const BorderRange r = UndistortedBorders(camera, MakePinhole(camera, p, width, height), source);
    const double w = static_cast<double>(width);
    const double h = static_cast<double>(height);
    // Scales at which the pinhole image reaches every distorted border pixel (no pixel lost) and
    // at which it stays inside all of them (no blank pixel), per axis.
    const double keep_all_x =
        std::min(p.cx / (p.cx - r.left_min), (w - 0.5 - p.cx) / (r.right_max - p.cx));
    const double keep_all_y =
        std::min(p.cy / (p.cy - r.top_min), (h - 0.5 - p.cy) / (r.bottom_max - p.cy));
    const double no_blank_x =
        std::max(p.cx / (p.cx - r.left_max), (w - 0.5 - p.cx) / (r.right_min - p.cx));
    const double no_blank_y =
        std::max(p.cy / (p.cy - r.top_max), (h - 0.5 - p.cy) / (r.bottom_min - p.cy));
    const double b = options.blank_pixels;
    const double scale_x = std::clamp(1.0 / (keep_all_x * b + no_blank_x * (1 - b)),
                                      options.min_scale, options.max_scale);
    const double scale_y = std::clamp(1.0 / (keep_all_y * b + no_blank_y * (1 - b)),
                                      options.min_scale, options.max_scale);
    width = static_cast<uint64_t>(std::max(1.0, scale_x * w));
    height = static_cast<uint64_t>(std::max(1.0, scale_y * h));
    p.cx *= static_cast<double>(width) / w;
    p.cy *= static_cast<double>(height) / h;
  }
  const uint64_t longest = std::max(width, height);
  if (options.max_image_size > 0 && longest > static_cast<uint64_t>(options.max_image_size)) {
    const double factor = static_cast<double>(options.max_image_size) / longest;
    const uint64_t new_width = static_cast<uint64_t>(std::max(1.0, std::round(width * factor)));
    const uint64_t new_height = static_cast<uint64_t>(std::max(1.0, std::round(height * factor)));
    const double sx = static_cast<double>(new_width) / width;
    const double sy = static_cast<double>(new_height) / height;
    p = {p.fx * sx, p.fy * sy, p.cx * sx, p.cy * sy};
    width = new_width;
    height = new_height;
  }
  return MakePinhole(camera, p, width, height);
}

}  // namespace ramap
