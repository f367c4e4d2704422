#include "ramap/estimators/bearings.h"

#include "ramap/geometry/camera_projection.h"

namespace ramap {

ImageBearings ComputeBearings(const FeatureDatabase& database, const std::string& source) {
  return ComputeBearings(database, database.cameras, source);
}

ImageBearings ComputeBearings(const FeatureDatabase& database,
                              const std::map<uint32_t, Camera>& cameras, const std::string& source,
                              const std::vector<uint32_t>& image_ids) {
  ImageBearings result;
  for (const auto& [camera_id, camera] : cameras) {
    CheckCameraParams(camera, source + ": camera " + std::to_string(camera_id));
    result.focal_lengths_px[camera_id] = MeanFocalLength(camera);
  }
  auto add = [&](uint32_t image_id, const Keypoints& keypoints) {
    const auto image = database.images.find(image_id);
    if (image == database.images.end()) return;
    const Camera& camera = cameras.at(image->second.camera_id);
    std::vector<Eigen::Vector3d>& bearings = result.bearings[image_id];
    bearings.reserve(keypoints.size());
    for (size_t k = 0; k < keypoints.size(); ++k)
      bearings.push_back(PixelToBearing(camera, keypoints.xy(k)));
  };
  if (image_ids.empty()) {
    for (const auto& [image_id, keypoints] : database.keypoints) add(image_id, keypoints);
  }
  for (const uint32_t image_id : image_ids) {
    const auto keypoints = database.keypoints.find(image_id);
    if (keypoints != database.keypoints.end()) add(image_id, keypoints->second);
  }
  return result;
}

}  // namespace ramap
