#include "ramap/refine/model_bundle_adjustment.h"

#include "ramap/geometry/camera_projection.h"
#include "ramap/util/error.h"

namespace ramap {

BundleAdjustmentSummary BundleAdjustModel(Reconstruction* model,
                                          const BundleAdjustmentOptions& options,
                                          const std::string& source) {
  std::map<uint32_t, double> focal_lengths_px;
  for (const auto& [camera_id, camera] : model->cameras) {
    CheckCameraParams(camera, source);
    focal_lengths_px[camera_id] = MeanFocalLength(camera);
  }
  // Bearings in double precision straight from the model's points2D.
  KeypointBearings bearings;
  size_t num_observations = 0;
  for (const auto& [image_id, image] : model->images) {
    const Camera& camera = model->cameras.at(image.camera_id);
    std::vector<Eigen::Vector3d>& image_bearings = bearings[image_id];
    image_bearings.reserve(image.points2D.size());
    for (const Point2D& point2D : image.points2D) {
      image_bearings.push_back(PixelToBearing(camera, point2D.xy));
      num_observations += point2D.point3D_id != kInvalidPoint3DId;
    }
  }
  if (num_observations == 0) {
    throw InputError(source, "the model has no observation of a 3D point to adjust");
  }
  // Every point: a capped adjustment would drop the others from the model written back.
  BundleAdjustmentOptions all_points = options;
  all_points.max_num_points = 0;
  all_points.min_track_length = 2;
  return BundleAdjust(bearings, focal_lengths_px, model, all_points);
}

}  // namespace ramap
