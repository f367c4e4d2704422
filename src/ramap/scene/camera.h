// Camera intrinsics as COLMAP stores them: a model id, image size and a parameter vector.
//
// Model ids and parameter orders are COLMAP's (src/base/camera_models.h in COLMAP 3.8), so that
// databases and models pass through unchanged. Projection and undistortion live in
// geometry/camera_projection.h.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ramap {

enum class CameraModel : int {
  kSimplePinhole = 0,        // f, cx, cy
  kPinhole = 1,              // fx, fy, cx, cy
  kSimpleRadial = 2,         // f, cx, cy, k
  kRadial = 3,               // f, cx, cy, k1, k2
  kOpenCV = 4,               // fx, fy, cx, cy, k1, k2, p1, p2
  kOpenCVFisheye = 5,        // fx, fy, cx, cy, k1, k2, k3, k4
  kFullOpenCV = 6,           // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6
  kFOV = 7,                  // fx, fy, cx, cy, omega
  kSimpleRadialFisheye = 8,  // f, cx, cy, k
  kRadialFisheye = 9,        // f, cx, cy, k1, k2
  kThinPrismFisheye = 10,    // fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, sx1, sy1
};

struct Camera {
  uint32_t camera_id = 0;
  CameraModel model = CameraModel::kPinhole;
  uint64_t width = 0;
  uint64_t height = 0;
  std::vector<double> params;
  bool has_prior_focal_length = false;
};

// Number of parameters of a model (e.g. 4 for PINHOLE).
int NumCameraParams(CameraModel model);
// COLMAP's name of a model, e.g. "SIMPLE_RADIAL".
std::string CameraModelName(CameraModel model);
// The model with COLMAP's name `name`, if there is one.
std::optional<CameraModel> CameraModelFromName(const std::string& name);
// The model with COLMAP's integer id, if there is one.
std::optional<CameraModel> CameraModelFromId(int id);

// Each camera mapped to the lowest id among those with the same model, size, parameters and prior
// flag: cameras from one source (a calibration given once, one EXIF value, one guess) that COLMAP
// writes one per image.
std::map<uint32_t, uint32_t> IdenticalCameras(const std::map<uint32_t, Camera>& cameras);

}  // namespace ramap
