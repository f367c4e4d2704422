#include "synthetic_options.h"

#include <map>

#include "options.h"
#include "ramap/io/trajectory.h"
#include "ramap/util/error.h"
#include "ramap/util/number_list.h"

namespace ramap::cli {

namespace {

// Revisits, view distance and aliasing: what makes a long synthetic drive look like a real one.
void AddDriveOptions(CLI::App& app, SyntheticSceneOptions* options) {
  app.add_option("--Synthetic.loop_radius_m", options->loop_max_distance,
                 "sequential: also match frames whose centres are this close (revisits; 0: none)")
      ->capture_default_str();
  app.add_option("--Synthetic.loop_min_frame_gap", options->loop_min_frame_gap,
                 "revisits are at least this many frames apart (0: at least 4 loop radii "
                 "travelled)")
      ->capture_default_str();
  app.add_option("--Synthetic.loop_max_angle_deg", options->loop_max_angle_deg,
                 "revisits look the same way within this angle")
      ->capture_default_str();
  app.add_option("--Synthetic.max_view_distance", options->max_view_distance,
                 "points farther from a camera are not seen by it (0: no limit; > 0 builds "
                 "thousands of frames fast)")
      ->capture_default_str();
  app.add_option("--Synthetic.num_aliased_pairs", options->num_aliased_pairs,
                 "pairs with consistent matches of a relative pose rotated off by an angle in "
                 "[aliased_min_angle_deg, aliased_max_angle_deg], as repetitive scenes gives")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_min_angle_deg", options->aliased_min_angle_deg,
                 "aliased pairs' rotations are off by at least this angle")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_max_angle_deg", options->aliased_max_angle_deg,
                 "and by at most this one (drawn uniformly between)")
      ->capture_default_str();
  app.add_option("--Synthetic.num_aliased_pair_matches", options->num_aliased_pair_matches,
                 "matches drawn per aliased pair (those leaving the second image are dropped)")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_max_frame_gap", options->aliased_max_frame_gap,
                 "aliased pairs are at most this many frames apart (0: any two frames)")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_shift_m", options->aliased_shift_m,
                 "aliased poses also move the second camera this far in a random direction, as "
                 "a repeated facade gives (0: the true translation)")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_matches_on_tracks", options->aliased_matches_on_tracks,
                 "1: aliased matches start from the first image's own observations, so they join "
                 "its points' tracks (0: new keypoints on no track)")
      ->capture_default_str();
  app.add_option("--Synthetic.aliased_pair_ratio", options->aliased_pair_ratio,
                 "the same as a fraction of the matched pairs (the larger count is used)")
      ->capture_default_str();
  app.add_option("--Synthetic.facade_distance_m", options->facade_distance,
                 "sequential: points on two facades this far left and right of the road (0: "
                 "anywhere in view)")
      ->capture_default_str();
  app.add_option("--Synthetic.facade_height_m", options->facade_height,
                 "facades rise this far above the camera")
      ->capture_default_str();
  app.add_option("--Synthetic.keypoint_columns", options->keypoint_columns,
                 "columns per stored keypoint: 2 (x, y), 4 (+ scale, orientation), 6 (+ affine "
                 "shape)")
      ->capture_default_str();
  app.add_option("--Synthetic.photo_names", options->photo_names,
                 "1: images named as unordered photos (photo_kqzb.jpg), not frame numbers")
      ->capture_default_str();
}

}  // namespace

void AddSceneOptions(CLI::App& app, SyntheticSceneOptions* options, SceneOptionText* text) {
  app.add_option("--Synthetic.layout", text->layout,
                 "sequential (a path) or unordered (around an object)")
      ->check(CLI::IsMember({"sequential", "unordered"}))
      ->capture_default_str();
  app.add_option("--Synthetic.path", text->path,
                 "sequential path: line (forward motion), circle (orbit of an object), loop (a "
                 "closed drive)")
      ->check(CLI::IsMember({"line", "circle", "loop"}))
      ->capture_default_str();
  app.add_option("--Synthetic.trajectory_path", text->trajectory_path,
                 "KITTI odometry pose file whose poses the sequential cameras take (instead of "
                 "--Synthetic.path); --Synthetic.num_images 0 takes all")
      ->check(CLI::ExistingFile);
  app.add_option("--Synthetic.num_images", options->num_images, "number of images")
      ->capture_default_str();
  app.add_option("--Synthetic.num_points", options->num_points, "number of random 3D points")
      ->capture_default_str();
  app.add_option("--Synthetic.pixel_noise", options->pixel_noise_sigma,
                 "standard deviation of keypoint noise, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.outlier_ratio", options->outlier_ratio,
                 "fraction of each pair's raw matches that are wrong")
      ->capture_default_str();
  app.add_option("--Synthetic.num_outlier_pairs", options->num_outlier_pairs,
                 "pairs with only wrong matches and a wrong verified geometry")
      ->capture_default_str();
  app.add_option("--Synthetic.overlap", options->overlap,
                 "sequential: match each image with its next N images")
      ->capture_default_str();
  AddDriveOptions(app, options);
  app.add_option("--Synthetic.min_num_inliers", options->min_num_inliers,
                 "fewest true matches of a pair with a two-view geometry")
      ->capture_default_str();
  app.add_option("--Synthetic.min_shared_points", options->min_shared_points,
                 "unordered: fewest shared points of a matched pair")
      ->capture_default_str();
  app.add_option("--Synthetic.step_length", options->step_length,
                 "generated paths: distance between frames")
      ->capture_default_str();
  app.add_option("--Synthetic.min_depth", options->min_depth, "nearest point depth")
      ->capture_default_str();
  app.add_option("--Synthetic.max_depth", options->max_depth, "farthest point depth")
      ->capture_default_str();
  text->camera_model = CameraModelName(options->camera.model);
  app.add_option("--Synthetic.camera_model", text->camera_model, "COLMAP camera model name")
      ->capture_default_str();
  app.add_option("--Synthetic.prior_focal_length", text->prior_focal_length,
                 "1: the database marks the focal length as known (a calibrated camera); 0: as a "
                 "guess, which the mapper calibrates")
      ->capture_default_str();
  app.add_option("--Synthetic.camera_params", text->camera_params,
                 "camera parameters in COLMAP's order, comma-separated")
      ->capture_default_str();
  app.add_option("--Synthetic.width", options->camera.width, "image width, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.height", options->camera.height, "image height, pixels")
      ->capture_default_str();
  app.add_option("--Synthetic.seed", options->seed, "random seed (same seed, same scene)")
      ->capture_default_str();
}

void FinishSceneOptions(const SceneOptionText& text, bool num_images_given,
                        SyntheticSceneOptions* options) {
  options->layout =
      text.layout == "unordered" ? SyntheticLayout::kUnordered : SyntheticLayout::kSequential;
  const std::map<std::string, SyntheticPath> paths = {{"line", SyntheticPath::kLine},
                                                      {"circle", SyntheticPath::kCircle},
                                                      {"loop", SyntheticPath::kLoop}};
  options->path = paths.at(text.path);
  const std::optional<CameraModel> model = CameraModelFromName(text.camera_model);
  if (!model) {
    throw InputError("--Synthetic.camera_model", "unknown model '" + text.camera_model + "'");
  }
  options->camera.model = *model;
  options->camera.params = ParseNumberList(text.camera_params, "--Synthetic.camera_params");
  options->camera.has_prior_focal_length = text.prior_focal_length;
  if (!text.trajectory_path.empty()) {
    if (options->layout != SyntheticLayout::kSequential) {
      throw InputError("--Synthetic.trajectory_path", "needs --Synthetic.layout sequential");
    }
    const GroundTruth trajectory = ReadGroundTruth(text.trajectory_path, GroundTruthFormat::kKitti);
    options->path = SyntheticPath::kGiven;
    for (const GroundTruthPose& pose : trajectory.poses) {
      options->given_poses.push_back(pose.cam_from_world);
    }
    if (!num_images_given) options->num_images = 0;
  }
  options->Check();
}

}  // namespace ramap::cli
