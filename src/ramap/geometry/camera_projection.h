// Projection of camera-frame points to pixels and back to bearing vectors through COLMAP 3.8's
// eleven camera models (parameter orders in scene/camera.h).
//
// The models follow COLMAP 3.8's equations (src/base/camera_models.h there): pinhole with radial /
// tangential (Brown-Conrady, as OpenCV), rational radial (FULL_OPENCV), the field-of-view model of
// Devernay & Faugeras, "Straight lines have to be straight", MVA 2001 (FOV), equidistant fisheye
// with polynomial radial distortion (Kannala & Brandt, PAMI 2006: OPENCV_FISHEYE and the
// *_RADIAL_FISHEYE models) and its thin-prism extension (Weng et al., PAMI 1992).
//
// Pixel coordinates are COLMAP's: the centre of the top-left pixel is (0.5, 0.5), the same frame as
// keypoints and the principal point, so no offset is applied anywhere.
#pragma once

#include <Eigen/Core>
#include <string>

#include "ramap/scene/camera.h"

namespace ramap {

// Whether the model maps the angle from the optical axis (equidistant fisheye) rather than the
// perspective ratio x/z: OPENCV_FISHEYE, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE, THIN_PRISM_FISHEYE.
bool IsFisheyeModel(CameraModel model);

// Pixel of a point given in camera coordinates (x right, y down, z forward), with distortion.
// Perspective models need z > 0; fisheye models accept any direction off the backward axis (as
// COLMAP for z > 0, extended continuously beyond 90 degrees). Returns NaN where the point has no
// image. Assumes valid params (CheckCameraParams).
Eigen::Vector2d ProjectToPixel(const Camera& camera, const Eigen::Vector3d& point_in_camera);

// Unit bearing vector (camera coordinates) of the ray through `pixel`, distortion removed by damped
// Newton iterations on the 2D distortion function (exact Jacobian by forward-mode differentiation,
// at most 100 iterations). Returns NaN when the pixel is outside the range where the model's
// distortion can be inverted (e.g. beyond the fold of a strong barrel distortion).
Eigen::Vector3d PixelToBearing(const Camera& camera, const Eigen::Vector2d& pixel);

// The pinhole part of the calibration, [fx 0 cx; 0 fy cy; 0 0 1] (distortion left out), with the
// focal lengths multiplied by `focal_scale`: F = K2^-T E K1^-1 and E = K2^T F K1 use it.
Eigen::Matrix3d CalibrationMatrix(const Camera& camera, double focal_scale = 1.0);

// The focal length in pixels, (fx + fy) / 2 for models with two.
double MeanFocalLength(const Camera& camera);

// Throws InputError(source, ...) when the parameter count does not match the model, a parameter
// is not finite, or a focal length is not positive.
void CheckCameraParams(const Camera& camera, const std::string& source);

}  // namespace ramap
