// The distortion functions of COLMAP 3.8's camera models, templated on the scalar type of the
// point and of the parameters, so that one definition serves projection, the Newton undistortion
// (ceres::Jet in the point) and bundle adjustment with refined intrinsics (ceres::Jet in both).
// Equations and references: geometry/camera_projection.h.
#pragma once

#include <cmath>
#include <limits>

#include "ramap/scene/camera.h"

namespace ramap {

// Models with a single focal length f (params f, cx, cy, ...); the others have fx, fy, cx, cy.
inline bool HasSingleFocalLength(CameraModel model) {
  switch (model) {
    case CameraModel::kSimplePinhole:
    case CameraModel::kSimpleRadial:
    case CameraModel::kRadial:
    case CameraModel::kSimpleRadialFisheye:
    case CameraModel::kRadialFisheye:
      return true;
    default:
      return false;
  }
}

// atan(x) / x as a function of x^2, smooth at 0 (where the series avoids the sqrt's infinite
// slope).
template <typename T>
T AtanRatio(const T& x2) {
  using std::atan;
  using std::sqrt;
  if (x2 < 1e-6) return 1.0 - x2 / 3.0 + x2 * x2 / 5.0;  // next term x^6/7 < 2e-19
  const T x = sqrt(x2);
  return atan(x) / x;
}

// Radial scale of the FOV model, r_d / r_u = atan(2 r_u tan(omega/2)) / (omega r_u), as a function
// of s = r_u^2; continuous as omega -> 0, where it becomes the pinhole.
template <typename T, typename K>
T FovScale(const K& omega, const T& s) {
  using std::abs;
  using std::tan;
  const K a = 2.0 * tan(0.5 * omega);
  const K a_over_omega = abs(omega) < 1e-6 ? K(1.0 + omega * omega / 12.0) : K(a / omega);
  return a_over_omega * AtanRatio<T>(a * a * s);
}

// The distortion function of each model on normalized coordinates (u, v): for perspective models
// u = x/z, v = y/z; for fisheye models (u, v) = theta * (x, y) / |(x, y)| (equidistant), which
// turns COLMAP's thetad / r factor into a polynomial in theta^2 = u^2 + v^2. Returns the distorted
// normalized coordinates, to be multiplied by the focal lengths.
template <typename T, typename K>
void Distort(CameraModel model, const K* k, const T& u, const T& v, T* ud, T* vd) {
  const T u2 = u * u;
  const T v2 = v * v;
  const T uv = u * v;
  const T s = u2 + v2;
  switch (model) {
    case CameraModel::kSimplePinhole:
    case CameraModel::kPinhole:
      *ud = u;
      *vd = v;
      return;
    case CameraModel::kSimpleRadial:
    case CameraModel::kSimpleRadialFisheye: {
      const T radial = 1.0 + k[0] * s;
      *ud = u * radial;
      *vd = v * radial;
      return;
    }
    case CameraModel::kRadial:
    case CameraModel::kRadialFisheye: {
      const T radial = 1.0 + s * (k[0] + k[1] * s);
      *ud = u * radial;
      *vd = v * radial;
      return;
    }
    case CameraModel::kOpenCV: {  // k1, k2, p1, p2
      const T radial = 1.0 + s * (k[0] + k[1] * s);
      *ud = u * radial + 2.0 * k[2] * uv + k[3] * (s + 2.0 * u2);
      *vd = v * radial + 2.0 * k[3] * uv + k[2] * (s + 2.0 * v2);
      return;
    }
    case CameraModel::kOpenCVFisheye: {  // k1..k4 on theta
      const T radial = 1.0 + s * (k[0] + s * (k[1] + s * (k[2] + s * k[3])));
      *ud = u * radial;
      *vd = v * radial;
      return;
    }
    case CameraModel::kFullOpenCV: {  // k1, k2, p1, p2, k3, k4, k5, k6
      const T radial =
          (1.0 + s * (k[0] + s * (k[1] + s * k[4]))) / (1.0 + s * (k[5] + s * (k[6] + s * k[7])));
      *ud = u * radial + 2.0 * k[2] * uv + k[3] * (s + 2.0 * u2);
      *vd = v * radial + 2.0 * k[3] * uv + k[2] * (s + 2.0 * v2);
      return;
    }
    case CameraModel::kFOV: {  // omega
      const T scale = FovScale<T, K>(k[0], s);
      *ud = u * scale;
      *vd = v * scale;
      return;
    }
    case CameraModel::kThinPrismFisheye: {  // k1, k2, p1, p2, k3, k4, sx1, sy1 on theta
      const T radial = 1.0 + s * (k[0] + s * (k[1] + s * (k[4] + s * k[5])));
      *ud = u * radial + 2.0 * k[2] * uv + k[3] * (s + 2.0 * u2) + k[6] * s;
      *vd = v * radial + 2.0 * k[3] * uv + k[2] * (s + 2.0 * v2) + k[7] * s;
      return;
    }
  }
  *ud = *vd = T(std::numeric_limits<double>::quiet_NaN());
}

// Pixel of a camera-frame point (x, y, z) under a perspective (non-fisheye) model with parameters
// `params` in COLMAP's order; false (pixel untouched) when the point is not in front of the camera.
// T and K may both be ceres::Jet: bundle adjustment differentiates through the intrinsics.
template <typename T, typename K>
bool ProjectPerspective(CameraModel model, const K* params, const T* point, T* pixel) {
  if (!(point[2] > 0.0)) return false;
  const bool single = HasSingleFocalLength(model);
  const K& fx = params[0];
  const K& fy = single ? params[0] : params[1];
  const K& cx = single ? params[1] : params[2];
  const K& cy = single ? params[2] : params[3];
  const T u = point[0] / point[2];
  const T v = point[1] / point[2];
  T ud, vd;
  Distort(model, params + (single ? 3 : 4), u, v, &ud, &vd);
  pixel[0] = fx * ud + cx;
  pixel[1] = fy * vd + cy;
  return true;
}

}  // namespace ramap
