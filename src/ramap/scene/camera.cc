#include "ramap/scene/camera.h"

#include <array>
#include <sstream>
#include <stdexcept>
#include <tuple>

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

std::map<uint32_t, uint32_t> IdenticalCameras(const std::map<uint32_t, Camera>& cameras) {
  std::map<uint32_t, uint32_t> identical;
  std::map<std::tuple<CameraModel, uint64_t, uint64_t, std::vector<double>, bool>, uint32_t>
      first_of;
  for (const auto& [camera_id, camera] : cameras) {
    const auto key = std::make_tuple(camera.model, camera.width, camera.height, camera.params,
                                     camera.has_prior_focal_length);
    identical[camera_id] = first_of.emplace(key, camera_id).first->second;
  }
  return identical;
}

}  // namespace ramap
