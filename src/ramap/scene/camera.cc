#include "ramap/scene/camera.h"

#include <array>
#include <sstream>
#include <stdexcept>

#include "ramap/util/error.h"

namespace ramap {
namespace {

struct ModelInfo {
  CameraModel model;
  const char* name;
  int num_params;
};

constexpr std::array<ModelInfo, 11> kModels = {{
    {CameraModel::kSimplePinhole, "SIMPLE_PINHOLE", 3},
    {CameraModel::kPinhole, "PINHOLE", 4},
    {CameraModel::kSimpleRadial, "SIMPLE_RADIAL", 4},
    {CameraModel::kRadial, "RADIAL", 5},
    {CameraModel::kOpenCV, "OPENCV", 8},
    {CameraModel::kOpenCVFisheye, "OPENCV_FISHEYE", 8},
    {CameraModel::kFullOpenCV, "FULL_OPENCV", 12},
    {CameraModel::kFOV, "FOV", 5},
    {CameraModel::kSimpleRadialFisheye, "SIMPLE_RADIAL_FISHEYE", 4},
    {CameraModel::kRadialFisheye, "RADIAL_FISHEYE", 5},
    {CameraModel::kThinPrismFisheye, "THIN_PRISM_FISHEYE", 12},
}};

const ModelInfo& Info(CameraModel model) { return kModels.at(static_cast<int>(model)); }

}  // namespace

int NumCameraParams(CameraModel model) { return Info(model).num_params; }

std::string CameraModelName(CameraModel model) { return Info(model).name; }

std::optional<CameraModel> CameraModelFromName(const std::string& name) {
  for (const ModelInfo& info : kModels) {
    if (name == info.name) return info.model;
  }
  return std::nullopt;
}

std::optional<CameraModel> CameraModelFromId(int id) {
  if (id < 0 || id >= static_cast<int>(kModels.size())) return std::nullopt;
  return kModels[id].model;
}

}  // namespace ramap
