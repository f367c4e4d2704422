#include "ramap/pipeline/refine.h"

#include <algorithm>
#include <map>

#include "ramap/pipeline/bearings.h"
#include "ramap/pipeline/mapper_options.h"
#include "ramap/pipeline/mapper_summary.h"
#include "ramap/pipeline/structure.h"

namespace ramap {

void RefineComponent(const MapperContext& context, const std::vector<Track>& tracks,
                     PriorAlignment* georegistration, MapperComponentSummary* component,
                     Reconstruction* reconstruction) {
  const MapperOptions& options = context.options;
  Reconstruction adjusted = PointsForBundleAdjustment(*reconstruction, options.bundle_adjustment);
  const bool use_priors =
      georegistration->summary.georegistered && options.georegistration.use_in_bundle_adjustment;
  component->bundle_adjustment =
      BundleAdjust(context.bearings.bearings, context.bearings.focal_lengths_px, &adjusted,
                   options.bundle_adjustment,
                   use_priors ? georegistration->inliers : std::map<uint32_t, PositionPrior>());
  georegistration->summary.used_in_bundle_adjustment = use_priors;
  const BundleAdjustmentSummary& ba = component->bundle_adjustment;
  context.log.Record(stage::kBundleAdjustment, ba.seconds,
                     std::to_string(ba.num_points) + " points, RMSE " +
                         std::to_string(ba.initial_rmse_px) + " -> " +
                         std::to_string(ba.final_rmse_px) + " px, " +
                         std::to_string(ba.num_iterations) + " iterations");
  std::map<uint32_t, Rigid3d> refined;
  std::vector<uint32_t> image_ids;
  for (const auto& [id, image] : adjusted.images) {
    refined[id] = image.cam_from_world;
    image_ids.push_back(id);
  }
  const bool intrinsics_refined =
      std::any_of(adjusted.cameras.begin(), adjusted.cameras.end(), [&](const auto& entry) {
        return RefinesIntrinsics(options.bundle_adjustment, entry.second.model);
      });
  if (!intrinsics_refined) {
    *reconstruction =
        TriangulateComponent(context, refined, tracks, context.bearings, context.cameras,
                             "again with the refined poses: ", component);
    return;
  }
  std::map<uint32_t, Camera> refined_cameras = context.cameras;
  for (const auto& [camera_id, camera] : adjusted.cameras) refined_cameras[camera_id] = camera;
  const ImageBearings refined_bearings =
      ComputeBearings(context.database, refined_cameras, "bundle adjustment", image_ids);
  *reconstruction =
      TriangulateComponent(context, refined, tracks, refined_bearings, refined_cameras,
                           "again with the refined poses and intrinsics: ", component);
}

}  // namespace ramap
