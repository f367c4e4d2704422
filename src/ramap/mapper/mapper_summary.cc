#include "ramap/mapper/mapper_summary.h"

namespace ramap {

std::vector<CameraIntrinsicsSummary> SummariseIntrinsics(
    const FeatureDatabase& database, const ViewGraphCalibrationSummary& calibration,
    const std::vector<Reconstruction>& reconstructions) {
  std::vector<CameraIntrinsicsSummary> cameras;
  for (const auto& [camera_id, camera] : database.cameras) {
    CameraIntrinsicsSummary entry;
    entry.camera_id = camera_id;
    entry.model = CameraModelName(camera.model);
    entry.prior_focal_length_known = camera.has_prior_focal_length;
    entry.prior_params = camera.params;
    entry.focal_source = camera.has_prior_focal_length
                             ? "database: given (prior_focal_length 1: EXIF or the user)"
                             : "database: a guess (prior_focal_length 0)";
    for (const CameraCalibration& estimate : calibration.cameras) {
      if (estimate.camera_id == camera_id) entry.view_graph = estimate;
    }
    for (const Reconstruction& reconstruction : reconstructions) {
      const auto written = reconstruction.cameras.find(camera_id);
      if (written == reconstruction.cameras.end()) continue;
      entry.final_params = written->second.params;
      entry.final_model = CameraModelName(written->second.model);
      break;
    }
    cameras.push_back(entry);
  }
  return cameras;
}

void ListUnregisteredImages(const FeatureDatabase& database,
                            const std::vector<Reconstruction>& reconstructions,
                            std::map<uint32_t, std::string>* image_reasons,
                            MapperSummary* summary) {
  for (const Reconstruction& reconstruction : reconstructions) {
    summary->num_registered_images += static_cast<int>(reconstruction.images.size());
    for (const auto& [id, image] : reconstruction.images) image_reasons->erase(id);
  }
  for (const auto& [id, reason] : *image_reasons)
    summary->dropped_images.push_back({database.images.at(id).name, reason});
}

}  // namespace ramap
