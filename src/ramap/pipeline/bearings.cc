#include "ramap/pipeline/bearings.h"

#include "ramap/geometry/camera_projection.h"

namespace ramap {

ImageBearings ComputeBearings(const FeatureDatabase& database, const std::string& source) {
  ImageBearings result;
  for (const auto& [camera_id, camera] : database.cameras) {
    CheckCameraParams(camera, source + ": camera " + std::to_string(camera_id));
    result.focal_lengths_px[camera_id] = MeanFocalLength(camera);
  }
  for (const auto& [image_id, keypoints] : database.keypoints) {
    const auto image = database.images.find(image_id);
    if (image == database.images.end()) continue;
    const Camera& camera = database.cameras.at(image->second.camera_id);
    std::vector<Eigen::Vector3d>& bearings = result.bearings[image_id];
    bearings.reserve(keypoints.size());
    for (size_t k = 0; k < keypoints.size(); ++k)
      bearings.push_back(PixelToBearing(camera, keypoints.xy(k)));
  }
  return result;
}

}  // namespace ramap
