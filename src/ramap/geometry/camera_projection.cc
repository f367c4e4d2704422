#include "ramap/geometry/camera_projection.h"

#include <ceres/jet.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <sstream>

#include "ramap/geometry/camera_distortion.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

struct Intrinsics {
  double fx = 1.0;
  double fy = 1.0;
  double cx = 0.0;
  double cy = 0.0;
  const double* extra = nullptr;  // distortion parameters, in the model's order
};

Intrinsics SplitParams(const Camera& camera) {
  const std::vector<double>& p = camera.params;
  Intrinsics in;
  if (HasSingleFocalLength(camera.model)) {
    in.fx = in.fy = p[0];
    in.cx = p[1];
    in.cy = p[2];
    in.extra = p.data() + 3;
  } else {
    in.fx = p[0];
    in.fy = p[1];
    in.cx = p[2];
    in.cy = p[3];
    in.extra = p.data() + 4;
  }
  return in;
}

void DistortWithJacobian(CameraModel model, const double* k, const Eigen::Vector2d& m,
                         Eigen::Vector2d* d, Eigen::Matrix2d* jacobian) {
  using Jet = ceres::Jet<double, 2>;
  Jet ud, vd;
  Distort(model, k, Jet(m.x(), 0), Jet(m.y(), 1), &ud, &vd);
  *d = Eigen::Vector2d(ud.a, vd.a);
  jacobian->row(0) = ud.v.transpose();
  jacobian->row(1) = vd.v.transpose();
}

// Solves Distort(m) = d for m. Newton with step halving, so that a step never increases the
// residual; starts from m = d, which is exact without distortion and close for lenses whose
// distortion is a perturbation of the identity.
bool Undistort(CameraModel model, const double* k, const Eigen::Vector2d& d, Eigen::Vector2d* m) {
  constexpr int kMaxIterations = 100;
  constexpr int kMaxHalvings = 30;
  const double scale = 1.0 + d.norm();
  *m = d;
  Eigen::Vector2d dm;
  Eigen::Matrix2d jacobian;
  DistortWithJacobian(model, k, *m, &dm, &jacobian);
  Eigen::Vector2d residual = dm - d;
  double residual_norm = residual.norm();
  const double converged = 4.0 * std::numeric_limits<double>::epsilon() * scale;
  for (int iteration = 0; iteration < kMaxIterations && residual_norm > converged; ++iteration) {
    const Eigen::Vector2d step = jacobian.partialPivLu().solve(residual);
    if (!step.allFinite()) break;
    bool improved = false;
    double t = 1.0;
    for (int halving = 0; halving < kMaxHalvings && !improved; ++halving, t *= 0.5) {
      const Eigen::Vector2d candidate = *m - t * step;
      Eigen::Vector2d candidate_d;
      Eigen::Matrix2d candidate_jacobian;
      DistortWithJacobian(model, k, candidate, &candidate_d, &candidate_jacobian);
      const double candidate_norm = (candidate_d - d).norm();
      if (candidate_norm < residual_norm) {
        *m = candidate;
        jacobian = candidate_jacobian;
        residual = candidate_d - d;
        residual_norm = candidate_norm;
        improved = true;
      }
    }
    // No decrease along the Newton direction: at the limit of double precision, or stuck.
    if (!improved) break;
  }
  // 1e-10 in normalized coordinates is well under 1e-6 pixels for any real focal length; a larger
  // residual means a local minimum of |Distort(m) - d|, i.e. no preimage near the start.
  return residual_norm <= 1e-10 * scale;
}

Eigen::Vector2d NaN2() {
  return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
}

}  // namespace

bool IsFisheyeModel(CameraModel model) {
  return model == CameraModel::kOpenCVFisheye || model == CameraModel::kSimpleRadialFisheye ||
         model == CameraModel::kRadialFisheye || model == CameraModel::kThinPrismFisheye;
}

Eigen::Vector2d ProjectToPixel(const Camera& camera, const Eigen::Vector3d& point_in_camera) {
  const Eigen::Vector3d& p = point_in_camera;
  Eigen::Vector2d m;
  if (IsFisheyeModel(camera.model)) {
    const double rho = std::hypot(p.x(), p.y());
    if (rho == 0.0) {
      if (!(p.z() > 0.0)) return NaN2();
      m.setZero();
    } else {
      const double theta = std::atan2(rho, p.z());
      m = (theta / rho) * p.head<2>();
    }
  } else {
    if (!(p.z() > 0.0)) return NaN2();
    m = p.head<2>() / p.z();
  }
  const Intrinsics in = SplitParams(camera);
  double ud = 0.0;
  double vd = 0.0;
  Distort(camera.model, in.extra, m.x(), m.y(), &ud, &vd);
  return Eigen::Vector2d(in.fx * ud + in.cx, in.fy * vd + in.cy);
}

Eigen::Vector3d PixelToBearing(const Camera& camera, const Eigen::Vector2d& pixel) {
  const Intrinsics in = SplitParams(camera);
  const Eigen::Vector2d d((pixel.x() - in.cx) / in.fx, (pixel.y() - in.cy) / in.fy);
  Eigen::Vector2d m;
  if (!Undistort(camera.model, in.extra, d, &m)) {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  if (!IsFisheyeModel(camera.model)) return Eigen::Vector3d(m.x(), m.y(), 1.0).normalized();
  const double theta = m.norm();
  // sin(theta) / theta, by its series where the division would lose digits.
  const double sinc = theta < 1e-4 ? 1.0 - theta * theta / 6.0 : std::sin(theta) / theta;
  return Eigen::Vector3d(sinc * m.x(), sinc * m.y(), std::cos(theta)).normalized();
}

Eigen::Matrix3d CalibrationMatrix(const Camera& camera, double focal_scale) {
  const Intrinsics in = SplitParams(camera);
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = focal_scale * in.fx;
  K(1, 1) = focal_scale * in.fy;
  K(0, 2) = in.cx;
  K(1, 2) = in.cy;
  return K;
}

double MeanFocalLength(const Camera& camera) {
  const Intrinsics in = SplitParams(camera);
  return 0.5 * (in.fx + in.fy);
}

void CheckCameraParams(const Camera& camera, const std::string& source) {
  const std::string what = "camera " + std::to_string(camera.camera_id);
  const int expected = NumCameraParams(camera.model);
  if (static_cast<int>(camera.params.size()) != expected) {
    std::ostringstream message;
    message << what << " (" << CameraModelName(camera.model) << ") has " << camera.params.size()
            << " parameters, the model needs " << expected;
    throw InputError(source, message.str());
  }
  for (size_t i = 0; i < camera.params.size(); ++i) {
    if (!std::isfinite(camera.params[i])) {
      throw InputError(source,
                       what + " has a non-finite parameter (index " + std::to_string(i) + ")");
    }
  }
  const Intrinsics in = SplitParams(camera);
  if (!(in.fx > 0.0) || !(in.fy > 0.0)) {
    std::ostringstream message;
    message << what << " has a non-positive focal length (" << in.fx;
    if (!HasSingleFocalLength(camera.model)) message << ", " << in.fy;
    message << ")";
    throw InputError(source, message.str());
  }
}

}  // namespace ramap
