#include <string>
#include <utility>
#include <vector>

#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "ramap/util/error.h"
#include "ramap/util/number_list.h"

namespace ramap {

namespace {

using Table = OptionTable<SyntheticSceneOptions>;
using Options = SyntheticSceneOptions;

template <typename Access>
OptionDeclaration<Options> Number(std::string name, Access access, OptionRange range,
                                  std::string help) {
  return NumberOption<Options>(std::move(name), access, range, std::move(help));
}

template <typename Access>
OptionDeclaration<Options> Bool(std::string name, Access access, std::string help) {
  return BoolOption<Options>(std::move(name), access, std::move(help));
}

// The shared camera: its model by COLMAP's name, its parameters as "a,b,c,...".
void DeclareCamera(Table& t) {
  OptionDeclaration<Options> model;
  model.name = "Synthetic.camera_model";
  model.type = OptionType::kText;
  model.help = "COLMAP camera model name";
  model.check = [](const std::string& text) -> std::string {
    return CameraModelFromName(text) ? "" : "unknown camera model '" + text + "'";
  };
  model.text = [](const Options& o) { return CameraModelName(o.camera.model); };
  model.store = [](Options& o, const std::string& text) {
    o.camera.model = *CameraModelFromName(text);
  };
  t.push_back(model);
  OptionDeclaration<Options> params;
  params.name = "Synthetic.camera_params";
  params.type = OptionType::kText;
  params.help = "camera parameters in COLMAP's order, comma-separated";
  params.check = [](const std::string& text) -> std::string {
    try {
      ParseNumberList(text, "--Synthetic.camera_params");
    } catch (const InputError&) {
      return "'" + text + "' is not a comma-separated list of numbers";
    }
    return "";
  };
  params.text = [](const Options& o) {
    std::string text;
    for (const double value : o.camera.params)
      text += (text.empty() ? "" : ",") + FormatOptionNumber(value);
    return text;
  };
  params.store = [](Options& o, const std::string& text) {
    o.camera.params = ParseNumberList(text, "--Synthetic.camera_params");
  };
  t.push_back(params);
  t.push_back(Bool(
      "Synthetic.prior_focal_length",
      [](auto& o) -> auto& { return o.camera.has_prior_focal_length; },
      "1: the database marks the focal length as known (a calibrated camera); 0: as "
      "a guess, which the mapper calibrates"));
  t.push_back(Number(
      "Synthetic.width", [](auto& o) -> auto& { return o.camera.width; }, AtLeast(1),
      "image width, pixels"));
  t.push_back(Number(
      "Synthetic.height", [](auto& o) -> auto& { return o.camera.height; }, AtLeast(1),
      "image height, pixels"));
}

void DeclareLayout(Table& t) {
  t.push_back(ChoiceOption<Options>(
      "Synthetic.layout", [](auto& o) -> auto& { return o.layout; },
      std::vector<std::pair<std::string, SyntheticLayout>>{
          {"sequential", SyntheticLayout::kSequential}, {"unordered", SyntheticLayout::kUnordered}},
      "sequential (a path) or unordered (around an object)"));
  t.push_back(ChoiceOption<Options>(
      "Synthetic.path", [](auto& o) -> auto& { return o.path; },
      std::vector<std::pair<std::string, SyntheticPath>>{{"line", SyntheticPath::kLine},
                                                         {"circle", SyntheticPath::kCircle},
                                                         {"loop", SyntheticPath::kLoop},
                                                         {"given", SyntheticPath::kGiven}},
      "sequential path: line (forward motion), circle (orbit of an object), loop (a closed "
      "drive), given (the poses of --Synthetic.trajectory_path, which sets it)"));
  t.push_back(Number(
      "Synthetic.num_images", [](auto& o) -> auto& { return o.num_images; }, AtLeast(0),
      "number of images (with a trajectory, 0 takes all its poses)"));
  t.push_back(Number(
      "Synthetic.num_points", [](auto& o) -> auto& { return o.num_points; }, AtLeast(1),
      "number of random 3D points"));
  t.push_back(Number(
      "Synthetic.pixel_noise", [](auto& o) -> auto& { return o.pixel_noise_sigma; }, AtLeast(0),
      "standard deviation of keypoint noise, pixels"));
  t.push_back(Number(
      "Synthetic.outlier_ratio", [](auto& o) -> auto& { return o.outlier_ratio; }, AtLeast(0, 0.9),
      "fraction of each pair's raw matches that are wrong"));
  t.push_back(Number(
      "Synthetic.num_outlier_pairs", [](auto& o) -> auto& { return o.num_outlier_pairs; },
      AtLeast(0), "pairs with only wrong matches and a wrong verified geometry"));
  t.push_back(Number(
      "Synthetic.overlap", [](auto& o) -> auto& { return o.overlap; }, AtLeast(1),
      "sequential: match each image with its next N images"));
  t.push_back(Number(
      "Synthetic.min_num_inliers", [](auto& o) -> auto& { return o.min_num_inliers; }, AtLeast(0),
      "fewest true matches of a pair with a two-view geometry"));
  t.push_back(Number(
      "Synthetic.min_shared_points", [](auto& o) -> auto& { return o.min_shared_points; },
      AtLeast(1), "unordered: fewest shared points of a matched pair"));
  t.push_back(Number(
      "Synthetic.step_length", [](auto& o) -> auto& { return o.step_length; }, Above(0),
      "generated paths: distance between frames"));
  t.push_back(Number(
      "Synthetic.min_depth", [](auto& o) -> auto& { return o.min_depth; }, Above(0),
      "nearest point depth"));
  t.push_back(Number(
      "Synthetic.max_depth", [](auto& o) -> auto& { return o.max_depth; }, Above(0),
      "farthest point depth (above min_depth)"));
  t.push_back(Number(
      "Synthetic.seed", [](auto& o) -> auto& { return o.seed; }, AtLeast(0),
      "random seed (same seed, same scene)"));
}

// Revisits, view distance and facades: what makes a long synthetic drive look like a real one.
void DeclareDrive(Table& t) {
  t.push_back(Number(
      "Synthetic.loop_radius_m", [](auto& o) -> auto& { return o.loop_max_distance; }, AtLeast(0),
      "sequential: also match frames whose centres are this close (revisits; 0: "
      "none)"));
  t.push_back(Number(
      "Synthetic.loop_min_frame_gap", [](auto& o) -> auto& { return o.loop_min_frame_gap; },
      AtLeast(0),
      "revisits are at least this many frames apart (0: at least 4 loop radii "
      "travelled)"));
  t.push_back(Number(
      "Synthetic.loop_max_angle_deg", [](auto& o) -> auto& { return o.loop_max_angle_deg; },
      AtLeast(0), "revisits look the same way within this angle"));
  t.push_back(Number(
      "Synthetic.max_view_distance", [](auto& o) -> auto& { return o.max_view_distance; },
      AtLeast(0),
      "points farther from a camera are not seen by it (0: no limit; > 0 builds "
      "thousands of frames fast)"));
  t.push_back(Number(
      "Synthetic.facade_distance_m", [](auto& o) -> auto& { return o.facade_distance; }, AtLeast(0),
      "sequential: points on two facades this far left and right of the road (0: "
      "anywhere in view)"));
  t.push_back(Number(
      "Synthetic.facade_height_m", [](auto& o) -> auto& { return o.facade_height; }, Above(0),
      "facades rise this far above the camera"));
  t.push_back(AlsoChecked(
      Number(
          "Synthetic.keypoint_columns", [](auto& o) -> auto& { return o.keypoint_columns; },
          AtLeast(2, 6),
          "columns per stored keypoint: 2 (x, y), 4 (+ scale, orientation), 6 (+ affine "
          "shape)"),
      [](const std::string& text) -> std::string {
        return text == "2" || text == "4" || text == "6" ? "" : "must be 2, 4 or 6, got " + text;
      }));
  t.push_back(Bool(
      "Synthetic.photo_names", [](auto& o) -> auto& { return o.photo_names; },
      "1: images named as unordered photos (photo_kqzb.jpg), not frame numbers"));
}

// Aliased pairs: verified matches of a wrong relative pose, as repeated structure gives.
void DeclareAliasing(Table& t) {
  t.push_back(Number(
      "Synthetic.num_aliased_pairs", [](auto& o) -> auto& { return o.num_aliased_pairs; },
      AtLeast(0),
      "pairs with consistent matches of a relative pose rotated off by an angle in "
      "[aliased_min_angle_deg, aliased_max_angle_deg], as repetitive scenes give"));
  t.push_back(Number(
      "Synthetic.aliased_pair_ratio", [](auto& o) -> auto& { return o.aliased_pair_ratio; },
      AtLeast(0, 1), "the same as a fraction of the matched pairs (the larger count is used)"));
  t.push_back(Number(
      "Synthetic.aliased_min_angle_deg", [](auto& o) -> auto& { return o.aliased_min_angle_deg; },
      AtLeast(0, 180), "aliased pairs' rotations are off by at least this angle"));
  t.push_back(Number(
      "Synthetic.aliased_max_angle_deg", [](auto& o) -> auto& { return o.aliased_max_angle_deg; },
      AtLeast(0, 180), "and by at most this one (drawn uniformly between)"));
  t.push_back(Number(
      "Synthetic.num_aliased_pair_matches",
      [](auto& o) -> auto& { return o.num_aliased_pair_matches; }, AtLeast(8),
      "matches drawn per aliased pair (those leaving the second image are "
      "dropped)"));
  t.push_back(Number(
      "Synthetic.aliased_max_frame_gap", [](auto& o) -> auto& { return o.aliased_max_frame_gap; },
      AtLeast(0), "aliased pairs are at most this many frames apart (0: any two frames)"));
  t.push_back(Number(
      "Synthetic.aliased_shift_m", [](auto& o) -> auto& { return o.aliased_shift_m; }, AtLeast(0),
      "aliased poses also move the second camera this far in a random direction, "
      "as a repeated facade gives (0: the true translation)"));
  t.push_back(Bool(
      "Synthetic.aliased_matches_on_tracks",
      [](auto& o) -> auto& { return o.aliased_matches_on_tracks; },
      "1: aliased matches start from the first image's own observations, so they "
      "join its points' tracks (0: new keypoints on no track)"));
  t.push_back(Bool(
      "Synthetic.aliased_symmetric", [](auto& o) -> auto& { return o.aliased_symmetric; },
      "1: aliased pairs join views from opposite sides of the object, matched as if the second "
      "were turned 180 degrees about the vertical axis (a landmark whose back looks like its "
      "front; orbit and unordered layouts)"));
}

}  // namespace

const OptionTable<SyntheticSceneOptions>& SyntheticSceneOptionTable() {
  static const Table table = [] {
    Table t;
    DeclareLayout(t);
    DeclareCamera(t);
    DeclareDrive(t);
    DeclareAliasing(t);
    return t;
  }();
  return table;
}

const OptionTable<SyntheticDescriptorOptions>& SyntheticDescriptorOptionTable() {
  static const OptionTable<SyntheticDescriptorOptions> table = {
      NumberOption<SyntheticDescriptorOptions>(
          "Synthetic.descriptor_noise", [](auto& o) -> auto& { return o.noise_sigma; }, AtLeast(0),
          "noise of a view's descriptor values (SIFT's scale: norm 512)")};
  return table;
}

}  // namespace ramap
