#include "ramap/mapper/component_triangulation.h"

#include "ramap/estimators/reregistration.h"
#include "ramap/util/timer.h"

namespace ramap {

Reconstruction TriangulateComponent(const PassInput& input,
                                    const std::map<uint32_t, Rigid3d>& poses,
                                    const std::vector<Track>& tracks, const ImageBearings& bearings,
                                    const std::map<uint32_t, Camera>& cameras,
                                    const std::string& what,
                                    const TrackTriangulationOptions& options,
                                    ComponentState* state) {
  Timer timer;
  TrackTriangulationSummary triangulated;
  Reconstruction reconstruction = BuildReconstruction(
      input.database, poses, tracks, bearings.bearings, bearings.focal_lengths_px, options,
      &triangulated, input.options.num_threads);
  for (auto& [camera_id, camera] : reconstruction.cameras) camera = cameras.at(camera_id);
  state->summary.num_points = triangulated.num_points;
  state->summary.num_observations = triangulated.num_observations;
  state->summary.mean_reprojection_error_px = triangulated.mean_reprojection_error_px;
  RecordStage(input, stage::kTriangulation, timer.ElapsedSeconds(),
              what + std::to_string(triangulated.num_points) + " points of " +
                  std::to_string(tracks.size()) + " tracks, mean reprojection error " +
                  std::to_string(triangulated.mean_reprojection_error_px) + " px",
              state);
  return reconstruction;
}

ComponentState TriangulateAveragedPoses(const PassInput& input, ComponentState state) {
  const PriorAlignment& prior_alignment = state.prior_alignment;
  for (const auto& [id, center] : state.translations->positions.centers) {
    const Eigen::Quaterniond& R = state.rotations.at(id);
    state.poses[id] = Rigid3d(R, -(R * center));
    if (prior_alignment.summary.aligned)
      state.poses[id] = TransformPose(prior_alignment.prior_from_model, state.poses[id]);
  }
  state.model =
      TriangulateComponent(input, state.poses, state.translations->tracks, input.bearings,
                           input.cameras, "", input.options.TriangulationOfAveragedPoses(), &state);
  return state;
}

ComponentState ReregisterComponent(const PassInput& input, ComponentState state) {
  const MapperOptions& options = input.options;
  if (!options.reregistration.enable) return state;
  Timer timer;
  const std::vector<Track>& tracks = state.translations->tracks;
  std::vector<ReregisteredImage>& tried = state.summary.reregistered_images;
  tried = ReregisterImages(tracks, input.bearings.bearings, input.bearings.focal_lengths_px,
                           state.model, options.reregistration,
                           options.triangulation.max_reprojection_error_px, &state.poses);
  int num_replaced = 0;
  for (const ReregisteredImage& image : tried) num_replaced += image.replaced;
  RecordStage(input, stage::kTriangulation, timer.ElapsedSeconds(),
              "re-registration: " + std::to_string(num_replaced) + " of " +
                  std::to_string(tried.size()) + " images its points left out placed again",
              &state);
  if (num_replaced == 0) return state;
  state.model = TriangulateComponent(
      input, state.poses, tracks, input.bearings, input.cameras,
      "again with the re-registered images: ", options.TriangulationOfAveragedPoses(), &state);
  return state;
}

}  // namespace ramap
