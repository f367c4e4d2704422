// Synthetic scenes with exact ground truth: a camera path or an unordered set of views, random 3D
// points the cameras see, noisy keypoints, matches with outliers and verified two-view geometries,
// as a COLMAP database would hold them, plus the true reconstruction.
//
// The builder is a pure function of its options (no file I/O; one std::mt19937_64 seeded from the
// options, so the same options give identical output). Unit and integration tests use it to check
// exact recovery without noise; `ramap synthesize` writes its output as a database and a model.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ramap/scene/camera.h"
#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/rigid3.h"
#include "ramap/util/option_table.h"

namespace ramap {

enum class SyntheticLayout {
  kSequential,  // frames along a path, matched with their next `overlap` frames and at revisits
  kUnordered,   // views around an object, matched exhaustively where they share points
};

enum class SyntheticPath {
  kLine,    // forward motion along +z, looking ahead (a car on a straight road)
  kCircle,  // an orbit around an object at the origin, looking at it (a turntable scan)
  kLoop,    // a closed circular drive looking ahead, ending where it started
  kGiven,   // SyntheticSceneOptions::given_poses, e.g. a KITTI ground-truth trajectory
};

struct SyntheticSceneOptions {
  SyntheticLayout layout = SyntheticLayout::kSequential;
  // Sequential layout only.
  SyntheticPath path = SyntheticPath::kLine;
  // cam_from_world poses for SyntheticPath::kGiven, in frame order (read by the caller).
  std::vector<Rigid3d> given_poses;

  // Number of images; for kGiven, 0 takes every given pose, else the first num_images.
  int num_images = 30;

  // One shared camera. Default: a VGA pinhole with a 65 degree horizontal field of view. Any
  // COLMAP model works (projection through geometry/camera_projection.h).
  Camera camera = DefaultCamera();
  // With a second camera (id 2; its camera_id is ignored), the even-numbered images (2, 4, ...)
  // are taken with it: two cameras of different intrinsics in one database. Same image size.
  std::optional<Camera> second_camera;

  // Number of random 3D points. Sequential paths (but the orbit): each is placed in the view of a
  // random frame at a random depth in [min_depth, max_depth]; orbit and unordered: on a shell
  // around an object of radius object_radius at the origin, seen only from its outer side.
  int num_points = 2000;
  double min_depth = 2.0;   // world units; generated paths move step_length per frame
  double max_depth = 30.0;  // world units

  // Generated paths: distance between consecutive frames (line, loop), world units.
  double step_length = 1.0;
  // Generated paths: random perturbation of each pose, so that the motion is not perfectly
  // regular (rotation in degrees, position in world units).
  double rotation_jitter_deg = 1.0;
  double position_jitter = 0.05;
  // Orbit and unordered views: object radius and camera distance from its centre.
  double object_radius = 3.0;
  double camera_distance = 10.0;

  // Gaussian noise on keypoints, pixels (0.5: typical SIFT localisation).
  double pixel_noise_sigma = 0.5;
  // Fraction of each pair's raw matches that are wrong correspondences (between extra keypoints
  // that observe no 3D point); they appear in `matches`, never in inlier_matches.
  double outlier_ratio = 0.1;
  // Image pairs whose matches are all random and whose stored two-view geometry is a random pose,
  // as a false positive of verification would look (listed in SyntheticScene::outlier_pair_ids).
  int num_outlier_pairs = 0;
  // Random matches of an outlier pair.
  int num_outlier_pair_matches = 50;

  // Sequential: each frame is matched with the next `overlap` frames...
  int overlap = 5;
  // ...and with earlier frames the path revisits: camera centres within loop_max_distance (world
  // units), viewing directions within loop_max_angle_deg, and more than 4 * loop_max_distance
  // travelled in between (so that standing still is not a revisit). 0 disables loop pairs.
  double loop_max_distance = 3.0;
  double loop_max_angle_deg = 30.0;
  // When > 0, a revisit needs at least this many frames between the two instead of the
  // travelled-distance rule (a KITTI drive: within 8 m and more than 100 frames apart).
  int loop_min_frame_gap = 0;
  // Points farther than this from a camera are not seen by it, as features fade with distance
  // (world units). 0: no limit. With a limit, each point is tested only against the cameras near
  // it, so that thousands of frames are built in seconds instead of minutes.
  double max_view_distance = 0.0;
  // Sequential paths but the orbit: when > 0, the points stand on two facades along the road
  // instead of anywhere in view: this far left and right of a random frame's camera (along its x
  // axis), from facade_height above it to 1.5 below (the ground; y points down), a random
  // distance in [min_depth, max_depth] ahead, with facade_roughness of noise across the facade
  // (windows, balconies). A street: near-planar facades on both sides, little in the middle.
  double facade_distance = 0.0;
  double facade_height = 10.0;
  double facade_roughness = 0.2;
  // Columns per stored keypoint: 2 (x, y), 4 (x, y, scale, orientation, as older COLMAP
  // databases hold SIFT) or 6 (x, y and an affine shape, as COLMAP writes SIFT). The extra
  // columns are random and do not change the scene.
  int keypoint_columns = 2;
  // Images named as unordered photos are ("photo_kqzb.jpg": letters from a random permutation of
  // the frames, no frame number) instead of frame_000001.png...: a collection, for the matching
  // plans that must not take it for a video.
  bool photo_names = false;
  // Aliased pairs, as repetitive scenes (facades, fences) gives: two frames that are not
  // matched by the layout get verified matches consistent with a relative pose whose rotation is
  // aliased_min_angle_deg to aliased_max_angle_deg off the true one (about a random axis). Their
  // number: num_aliased_pairs, or aliased_pair_ratio of the pairs matched otherwise, whichever is
  // larger (listed in SyntheticScene::aliased_pair_ids).
  int num_aliased_pairs = 0;
  double aliased_pair_ratio = 0.0;
  double aliased_min_angle_deg = 0.0;
  double aliased_max_angle_deg = 40.0;
  // Matches of an aliased pair (before those falling outside the second image are left out).
  int num_aliased_pair_matches = 100;
  // Aliased pairs of a sequence are at most this many frames apart (0: any two frames).
  int aliased_max_frame_gap = 0;
  // The aliased pose's second camera is also displaced by this distance in a random direction,
  // as a facade's repeat seen from elsewhere gives (0: the true translation).
  double aliased_shift_m = 0.0;
  // The first image's side of each aliased match is one of its own observations of a scene point,
  // so the wrong match joins that point's track, as real repeated features do (false: new
  // keypoints at random pixels and depths, on no track).
  bool aliased_matches_on_tracks = false;
  // Symmetric aliasing, as a landmark whose back looks like its front gives (orbit and unordered
  // layouts): an aliased pair is a view and one from about the other side of the object, whose
  // matches obey the second camera turned 180 degrees about the object's vertical axis (y through
  // the origin). The angle and shift settings above are then unused.
  bool aliased_symmetric = false;
  // Unordered: pairs sharing at least this many points are matched.
  int min_shared_points = 30;
  // A matched pair gets a two-view geometry when it has at least this many true matches (COLMAP's
  // TwoViewGeometryOptions::min_num_inliers default).
  int min_num_inliers = 15;

  uint64_t seed = 1;

  static Camera DefaultCamera();
  // Throws InputError("--Synthetic.<option>", ...) on a value out of range
  // ("SyntheticSceneOptions::<field>" for settings no command line reaches).
  void Check() const;
};

// Its options (--Synthetic.*), each declared once with its range and help (util/option_table.h):
// the command line, Check() and Python read them.
const OptionTable<SyntheticSceneOptions>& SyntheticSceneOptionTable();

struct SyntheticScene {
  // One camera (id 1; two with second_camera), images 1..N named frame_000001.png... in order
  // (or photo names),
  // keypoints (float32 x, y), raw matches (true and wrong, shuffled) and two-view geometries
  // (config CALIBRATED, inlier_matches the true matches, E, F, cam2_from_cam1 with unit
  // translation) for pairs with image_id1 < image_id2. No descriptors.
  FeatureDatabase database;
  // The truth: every image registered with its pose; points3D seen by at least two images with
  // their full tracks; points2D are the keypoints (in double precision) with their point3D ids.
  Reconstruction ground_truth;
  // Pair ids of the num_outlier_pairs pairs whose matches and geometry are wrong.
  std::vector<uint64_t> outlier_pair_ids;
  // Pair ids of the aliased pairs: verified, consistent, and wrong in rotation.
  std::vector<uint64_t> aliased_pair_ids;
};

// Throws InputError when options.Check() fails.
SyntheticScene BuildSyntheticScene(const SyntheticSceneOptions& options);

}  // namespace ramap
