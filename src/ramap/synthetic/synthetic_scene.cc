#include "ramap/synthetic/synthetic_scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

#include "ramap/geometry/camera_projection.h"
#include "ramap/geometry/rotation.h"
#include "ramap/util/error.h"
#include "ramap/util/option_check.h"

namespace ramap {
namespace {

using Rng = std::mt19937_64;

double Uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

double Gaussian(Rng& rng, double sigma) {
  if (sigma <= 0.0) return 0.0;
  return std::normal_distribution<double>(0.0, sigma)(rng);
}

Eigen::Vector3d GaussianVector(Rng& rng, double sigma) {
  const double x = Gaussian(rng, sigma);
  const double y = Gaussian(rng, sigma);
  const double z = Gaussian(rng, sigma);
  return Eigen::Vector3d(x, y, z);
}

Eigen::Vector3d RandomUnitVector(Rng& rng) {
  Eigen::Vector3d v;
  do {
    v = GaussianVector(rng, 1.0);
  } while (v.norm() < 1e-6);
  return v.normalized();
}

Eigen::Quaterniond RandomRotation(Rng& rng) {
  Eigen::Vector4d q;
  do {
    q = Eigen::Vector4d(Gaussian(rng, 1.0), Gaussian(rng, 1.0), Gaussian(rng, 1.0),
                        Gaussian(rng, 1.0));
  } while (q.norm() < 1e-6);
  q.normalize();
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

// A camera at `center` looking along `forward`, image x to the right and y down, where the world
// is y-down too (as KITTI's camera frame): forward along +z gives the identity rotation.
Rigid3d PoseFromCenterAndForward(const Eigen::Vector3d& center, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z);
  // Looking straight up or down: any right vector will do.
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitZ().cross(z);
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d world_from_cam;
  world_from_cam << x, y, z;
  const Eigen::Quaterniond rotation(world_from_cam.transpose());
  return Rigid3d(rotation, -(rotation * center));
}

// Rotates the camera by a small random rotation about its own centre.
Rigid3d JitterRotation(const Rigid3d& cam_from_world, double sigma_rad, Rng& rng) {
  const Eigen::Vector3d center = CameraCenter(cam_from_world);
  const Eigen::Vector3d axis_angle = GaussianVector(rng, sigma_rad);
  Eigen::Quaterniond jitter = Eigen::Quaterniond::Identity();
  if (axis_angle.norm() > 0.0) {
    jitter = Eigen::Quaterniond(Eigen::AngleAxisd(axis_angle.norm(), axis_angle.normalized()));
  }
  const Eigen::Quaterniond rotation = (jitter * cam_from_world.rotation).normalized();
  return Rigid3d(rotation, -(rotation * center));
}

std::vector<Rigid3d> MakePoses(const SyntheticSceneOptions& options, Rng& rng) {
  if (options.layout == SyntheticLayout::kSequential && options.path == SyntheticPath::kGiven) {
    const size_t n = options.num_images == 0 ? options.given_poses.size()
                                             : static_cast<size_t>(options.num_images);
    return std::vector<Rigid3d>(options.given_poses.begin(), options.given_poses.begin() + n);
  }
  const int n = options.num_images;
  const double rotation_sigma = options.rotation_jitter_deg * kDegToRad;
  std::vector<Rigid3d> poses;
  poses.reserve(n);
  for (int i = 0; i < n; ++i) {
    Rigid3d pose;
    if (options.layout == SyntheticLayout::kUnordered) {
      // Views from all around but not from straight above or below.
      Eigen::Vector3d direction;
      do {
        direction = RandomUnitVector(rng);
      } while (std::abs(direction.y()) > 0.8);
      const Eigen::Vector3d target = GaussianVector(rng, 0.1 * options.object_radius);
      const Eigen::Vector3d center = options.camera_distance * direction;
      pose = PoseFromCenterAndForward(center, target - center);
    } else {
      const double phi = 2.0 * M_PI * i / n;
      Eigen::Vector3d center = Eigen::Vector3d::Zero();
      Eigen::Vector3d forward = Eigen::Vector3d::UnitZ();
      switch (options.path) {
        case SyntheticPath::kLine:
          center = Eigen::Vector3d(0.0, 0.0, i * options.step_length);
          forward = Eigen::Vector3d::UnitZ();
          break;
        case SyntheticPath::kCircle: {
          // 15 degrees above the object's equator (y is down), one full turn.
          const double elevation = 15.0 * kDegToRad;
          const double r = options.camera_distance;
          center =
              Eigen::Vector3d(r * std::cos(elevation) * std::sin(phi), -r * std::sin(elevation),
                              r * std::cos(elevation) * std::cos(phi));
          forward = -center;
          break;
        }
        case SyntheticPath::kLoop: {
          // A circle of circumference n * step_length through the origin, heading +z there.
          const double r = n * options.step_length / (2.0 * M_PI);
          center = Eigen::Vector3d(r * (1.0 - std::cos(phi)), 0.0, r * std::sin(phi));
          forward = Eigen::Vector3d(std::sin(phi), 0.0, std::cos(phi));
          break;
        }
        case SyntheticPath::kGiven:
          break;  // handled above
      }
      center += GaussianVector(rng, options.position_jitter);
      pose = PoseFromCenterAndForward(center, forward);
    }
    poses.push_back(JitterRotation(pose, rotation_sigma, rng));
  }
  return poses;
}

// Whether points lie on an object at the origin (seen from outside) rather than along a path.
bool UsesObjectPoints(const SyntheticSceneOptions& options) {
  return options.layout == SyntheticLayout::kUnordered || options.path == SyntheticPath::kCircle;
}

// A point on the left or right facade of a street, in the frame of a camera looking down it.
Eigen::Vector3d FacadePoint(const SyntheticSceneOptions& options, Rng& rng) {
  constexpr double kGroundBelowCamera = 1.5;
  const double side = Uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  const double across = side * options.facade_distance + Gaussian(rng, options.facade_roughness);
  return Eigen::Vector3d(across, Uniform(rng, -options.facade_height, kGroundBelowCamera),
                         Uniform(rng, options.min_depth, options.max_depth));
}

std::vector<Eigen::Vector3d> MakePoints(const SyntheticSceneOptions& options,
                                        const std::vector<Rigid3d>& poses, Rng& rng) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(options.num_points);
  const Camera& camera = options.camera;
  for (int j = 0; j < options.num_points; ++j) {
    if (UsesObjectPoints(options)) {
      // A shell of thickness 0.2 r: a rough object surface.
      const double r = options.object_radius * Uniform(rng, 0.8, 1.0);
      points.push_back(r * RandomUnitVector(rng));
      continue;
    }
    // In the view of a random frame, so that every part of any path has landmarks in front of it.
    const size_t frame = std::uniform_int_distribution<size_t>(0, poses.size() - 1)(rng);
    if (options.facade_distance > 0) {
      points.push_back(poses[frame].Inverse() * FacadePoint(options, rng));
      continue;
    }
    const double x = Uniform(rng, 0.0, static_cast<double>(camera.width));
    const double y = Uniform(rng, 0.0, static_cast<double>(camera.height));
    const double distance = Uniform(rng, options.min_depth, options.max_depth);
    Eigen::Vector3d bearing = PixelToBearing(camera, Eigen::Vector2d(x, y));
    if (!bearing.allFinite()) bearing = Eigen::Vector3d::UnitZ();
    points.push_back(poses[frame].Inverse() * (distance * bearing));
  }
  return points;
}

// Inside [0, width) x [0, height), also once rounded to the float32 a keypoint is stored as.
bool InsideImage(const Camera& camera, const Eigen::Vector2d& xy) {
  return xy.allFinite() && xy.x() >= 0.0 && xy.y() >= 0.0 &&
         static_cast<float>(xy.x()) < static_cast<float>(camera.width) &&
         static_cast<float>(xy.y()) < static_cast<float>(camera.height);
}

// An observation of point `point_idx` as keypoint `point2D_idx` of its image.
struct Observation {
  uint32_t point_idx = 0;
  uint32_t point2D_idx = 0;
};

// True matches of two images: their observations of the same points (both lists are sorted by
// point index, so a merge finds them).
std::vector<FeatureMatch> SharedObservations(const std::vector<Observation>& a,
                                             const std::vector<Observation>& b) {
  std::vector<FeatureMatch> matches;
  size_t i = 0;
  size_t k = 0;
  while (i < a.size() && k < b.size()) {
    if (a[i].point_idx < b[k].point_idx) {
      ++i;
    } else if (b[k].point_idx < a[i].point_idx) {
      ++k;
    } else {
      matches.push_back({a[i].point2D_idx, b[k].point2D_idx});
      ++i;
      ++k;
    }
  }
  return matches;
}

Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Geometry of a pair from its relative pose, translation scaled to unit length as a two-view
// estimate can only give it.
TwoViewGeometry MakeGeometry(uint32_t image_id1, uint32_t image_id2, const Rigid3d& cam2_from_cam1,
                             const Eigen::Matrix3d& K1, const Eigen::Matrix3d& K2) {
  TwoViewGeometry geometry;
  geometry.image_id1 = image_id1;
  geometry.image_id2 = image_id2;
  geometry.cam2_from_cam1 = cam2_from_cam1;
  const Eigen::Matrix3d R = cam2_from_cam1.rotation.toRotationMatrix();
  const double baseline = cam2_from_cam1.translation.norm();
  if (baseline > 0.0) {
    geometry.config = TwoViewConfig::kCalibrated;
    geometry.cam2_from_cam1.translation /= baseline;
    geometry.E = CrossMatrix(geometry.cam2_from_cam1.translation) * R;
    geometry.F = K2.inverse().transpose() * geometry.E * K1.inverse();
  } else {
    // No baseline (a vehicle standing still): only a rotation, which COLMAP calls panoramic.
    geometry.config = TwoViewConfig::kPanoramic;
    geometry.H = K2 * R * K1.inverse();
  }
  return geometry;
}

std::string FrameName(size_t index) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%06zu.png", index + 1);
  return name;
}

// Names without a frame number: four letters, from a random permutation of the images.
std::vector<std::string> PhotoNames(size_t count, uint64_t seed) {
  std::vector<size_t> order(count);
  for (size_t k = 0; k < count; ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), Rng(seed ^ 0x9407015ull));
  std::vector<std::string> names;
  for (const size_t k : order) {
    std::string letters;
    for (size_t rest = k, n = 0; n < 4; ++n, rest /= 26)
      letters += static_cast<char>('a' + rest % 26);
    names.push_back("photo_" + letters + ".jpg");
  }
  return names;
}

void CheckPositive(double value, const std::string& field) {
  CheckOption(value > 0.0 && std::isfinite(value), "SyntheticSceneOptions::" + field,
              "a finite number > 0", value);
}

void CheckNonNegative(double value, const std::string& field) {
  CheckOption(value >= 0.0 && std::isfinite(value), "SyntheticSceneOptions::" + field,
              "a finite number >= 0", value);
}

// A trajectory's poses: at least two, finite rigid transforms, num_images of them at most.
void CheckGivenPoses(const SyntheticSceneOptions& o) {
  if (o.given_poses.size() < 2) {
    throw InputError("SyntheticSceneOptions::given_poses",
                     "needs at least 2 given poses, got " + std::to_string(o.given_poses.size()));
  }
  if (o.num_images < 0 || static_cast<size_t>(o.num_images) > o.given_poses.size() ||
      o.num_images == 1) {
    throw InputError("--Synthetic.num_images", "must be 0 (all) or between 2 and the " +
                                                   std::to_string(o.given_poses.size()) +
                                                   " poses of --Synthetic.trajectory_path, got " +
                                                   std::to_string(o.num_images));
  }
  for (const Rigid3d& pose : o.given_poses) {
    if (!pose.rotation.coeffs().allFinite() || !pose.translation.allFinite() ||
        std::abs(pose.rotation.norm() - 1.0) > 1e-6) {
      throw InputError("SyntheticSceneOptions::given_poses",
                       "a given pose is not a finite rigid transform");
    }
  }
}

}  // namespace

Camera SyntheticSceneOptions::DefaultCamera() {
  Camera camera;
  camera.camera_id = 1;
  camera.model = CameraModel::kPinhole;
  camera.width = 640;
  camera.height = 480;
  camera.params = {500.0, 500.0, 320.0, 240.0};
  return camera;
}

void SyntheticSceneOptions::Check() const {
  CheckOptionValues(SyntheticSceneOptionTable(), *this);
  if (layout == SyntheticLayout::kSequential && path == SyntheticPath::kGiven) {
    CheckGivenPoses(*this);
  } else {
    CheckOption(num_images >= 2, "--Synthetic.num_images",
                ">= 2 (0 takes every pose of --Synthetic.trajectory_path)", num_images);
  }
  CheckCameraParams(camera, "Synthetic.camera");
  if (second_camera) {
    CheckCameraParams(*second_camera, "Synthetic.second_camera");
    if (second_camera->width != camera.width || second_camera->height != camera.height) {
      throw InputError("SyntheticSceneOptions::second_camera",
                       "must have the first camera's image size");
    }
  }
  CheckOption(max_depth > min_depth, "--Synthetic.max_depth", "> --Synthetic.min_depth", max_depth);
  CheckOption(aliased_min_angle_deg <= aliased_max_angle_deg, "--Synthetic.aliased_min_angle_deg",
              "<= --Synthetic.aliased_max_angle_deg", aliased_min_angle_deg);
  CheckOption(
      !aliased_symmetric || UsesObjectPoints(*this), "--Synthetic.aliased_symmetric",
      "0 unless --Synthetic.layout is unordered or --Synthetic.path circle (it turns the object)",
      aliased_symmetric);
  CheckOption(!photo_names || num_images <= 26 * 26 * 26 * 26, "--Synthetic.num_images",
              "at most 456976 with --Synthetic.photo_names (four letters)", num_images);
  // The settings no command line option reaches.
  CheckNonNegative(rotation_jitter_deg, "rotation_jitter_deg");
  CheckNonNegative(position_jitter, "position_jitter");
  CheckPositive(object_radius, "object_radius");
  CheckOption(camera_distance > object_radius && std::isfinite(camera_distance),
              "SyntheticSceneOptions::camera_distance", "> object_radius", camera_distance);
  CheckOption(num_outlier_pair_matches >= 1, "SyntheticSceneOptions::num_outlier_pair_matches",
              ">= 1", num_outlier_pair_matches);
  CheckNonNegative(facade_roughness, "facade_roughness");
}

namespace {

// Image i (0-based) is taken with camera 1, or camera 2 for odd i with a second camera.
uint32_t CameraIdOf(const SyntheticSceneOptions& options, size_t i) {
  return options.second_camera && i % 2 ? 2 : 1;
}

const Camera& CameraOf(const SyntheticSceneOptions& options, size_t i) {
  return CameraIdOf(options, i) == 2 ? *options.second_camera : options.camera;
}

// What the cameras see: keypoints per image, each image's observations of the points, each
// point's track and the sum of its pixel noise.
struct SceneObservations {
  std::vector<std::vector<Point2D>> points2D;
  std::vector<std::vector<Observation>> observations;
  std::vector<std::vector<TrackElement>> tracks;
  std::vector<double> noise_sum;
};

// Observes point `j` in image `i` when it is in front of the camera (not closer than half the
// minimum depth, which no real camera could focus on, nor beyond max_view_distance), facing the
// camera on an object, and inside the image after noise.
void ObservePoint(const SyntheticSceneOptions& options, const std::vector<Rigid3d>& poses,
                  const std::vector<Eigen::Vector3d>& centers,
                  const std::vector<Eigen::Vector3d>& points, size_t j, size_t i, Rng& rng,
                  SceneObservations* seen) {
  if (UsesObjectPoints(options) && points[j].dot(centers[i] - points[j]) <= 0.0) return;
  const Eigen::Vector3d in_camera = poses[i] * points[j];
  if (in_camera.norm() < 0.5 * options.min_depth) return;
  if (options.max_view_distance > 0.0 && in_camera.norm() > options.max_view_distance) return;
  const Camera& camera = CameraOf(options, i);
  const Eigen::Vector2d projection = ProjectToPixel(camera, in_camera);
  if (!InsideImage(camera, projection)) return;
  const double dx = Gaussian(rng, options.pixel_noise_sigma);
  const double dy = Gaussian(rng, options.pixel_noise_sigma);
  const Eigen::Vector2d observed = projection + Eigen::Vector2d(dx, dy);
  if (!InsideImage(camera, observed)) return;
  const uint32_t point2D_idx = static_cast<uint32_t>(seen->points2D[i].size());
  Point2D point2D;
  point2D.xy = observed;
  seen->points2D[i].push_back(point2D);
  seen->observations[i].push_back({static_cast<uint32_t>(j), point2D_idx});
  seen->tracks[j].push_back({static_cast<uint32_t>(i + 1), point2D_idx});
  seen->noise_sum[j] += std::hypot(dx, dy);
}

// The cameras whose centres lie in the cells of a grid of max_view_distance around a point: the
// only ones that can see it.
class CameraGrid {
 public:
  CameraGrid(const std::vector<Eigen::Vector3d>& centers, double cell) : cell_(cell) {
    for (size_t i = 0; i < centers.size(); ++i) cells_[Key(Cell(centers[i]))].push_back(i);
  }

  // In increasing index order, so that tracks list their images in order.
  std::vector<size_t> Near(const Eigen::Vector3d& point) const {
    std::vector<size_t> near;
    const Eigen::Vector3i center = Cell(point);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find(Key(center + Eigen::Vector3i(dx, dy, dz)));
          if (found != cells_.end())
            near.insert(near.end(), found->second.begin(), found->second.end());
        }
      }
    }
    std::sort(near.begin(), near.end());
    return near;
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& x) const {
    return (x / cell_).array().floor().cast<int>();
  }
  static uint64_t Key(const Eigen::Vector3i& c) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(c.x()) & 0x1fffff) << 42) |
           (static_cast<uint64_t>(static_cast<uint32_t>(c.y()) & 0x1fffff) << 21) |
           (static_cast<uint64_t>(static_cast<uint32_t>(c.z()) & 0x1fffff));
  }

  double cell_;
  std::unordered_map<uint64_t, std::vector<size_t>> cells_;
};

// Every point in every camera that sees it (only the cameras near it with max_view_distance).
SceneObservations ObservePoints(const SyntheticSceneOptions& options,
                                const std::vector<Rigid3d>& poses,
                                const std::vector<Eigen::Vector3d>& centers,
                                const std::vector<Eigen::Vector3d>& points, Rng& rng) {
  const size_t num_images = poses.size();
  SceneObservations seen;
  seen.points2D.resize(num_images);
  seen.observations.resize(num_images);
  seen.tracks.resize(points.size());
  seen.noise_sum.assign(points.size(), 0.0);
  if (options.max_view_distance > 0.0) {
    const CameraGrid grid(centers, options.max_view_distance);
    for (size_t j = 0; j < points.size(); ++j) {
      for (const size_t i : grid.Near(points[j]))
        ObservePoint(options, poses, centers, points, j, i, rng, &seen);
    }
    return seen;
  }
  for (size_t j = 0; j < points.size(); ++j) {
    for (size_t i = 0; i < num_images; ++i)
      ObservePoint(options, poses, centers, points, j, i, rng, &seen);
  }
  return seen;
}

// Pairs to match, as (index1, index2) with index1 < index2: every pair of an unordered
// collection; for a sequence the next `overlap` frames and the revisits (close, looking the same
// way, far along the path).
std::set<std::pair<size_t, size_t>> CandidatePairs(const SyntheticSceneOptions& options,
                                                   const std::vector<Rigid3d>& poses,
                                                   const std::vector<Eigen::Vector3d>& centers) {
  const size_t num_images = poses.size();
  std::set<std::pair<size_t, size_t>> candidates;
  if (options.layout != SyntheticLayout::kSequential) {
    for (size_t i = 0; i < num_images; ++i) {
      for (size_t k = i + 1; k < num_images; ++k) candidates.insert({i, k});
    }
    return candidates;
  }
  for (size_t i = 0; i < num_images; ++i) {
    for (size_t k = 1; k <= static_cast<size_t>(options.overlap) && i + k < num_images; ++k) {
      candidates.insert({i, i + k});
    }
  }
  if (!(options.loop_max_distance > 0.0)) return candidates;
  std::vector<double> travelled(num_images, 0.0);
  for (size_t i = 1; i < num_images; ++i) {
    travelled[i] = travelled[i - 1] + (centers[i] - centers[i - 1]).norm();
  }
  const double cos_max_angle = std::cos(options.loop_max_angle_deg * kDegToRad);
  for (size_t i = 0; i < num_images; ++i) {
    const Eigen::Vector3d axis_i = poses[i].rotation.conjugate() * Eigen::Vector3d::UnitZ();
    for (size_t k = i + options.overlap + 1; k < num_images; ++k) {
      if ((centers[k] - centers[i]).norm() > options.loop_max_distance) continue;
      if (options.loop_min_frame_gap > 0
              ? k - i <= static_cast<size_t>(options.loop_min_frame_gap)
              : travelled[k] - travelled[i] <= 4.0 * options.loop_max_distance)
        continue;
      const Eigen::Vector3d axis_k = poses[k].rotation.conjugate() * Eigen::Vector3d::UnitZ();
      if (axis_i.dot(axis_k) < cos_max_angle) continue;
      candidates.insert({i, k});
    }
  }
  return candidates;
}

// A wrong correspondence joins two keypoints that observe nothing (clutter), one-to-one; returns
// the new keypoint's index.
uint32_t AddClutterKeypoint(const Camera& camera, Rng& rng, std::vector<Point2D>* points2D) {
  Point2D point2D;
  // A margin keeps the float32 keypoint below the image size.
  point2D.xy = Eigen::Vector2d(Uniform(rng, 0.0, camera.width - 0.01),
                               Uniform(rng, 0.0, camera.height - 0.01));
  points2D->push_back(point2D);
  return static_cast<uint32_t>(points2D->size() - 1);
}

// The candidate pairs that share enough points, with their true matches, clutter matches at the
// outlier ratio and the true two-view geometry. Returns the pairs matched.
std::set<std::pair<size_t, size_t>> AddMatchedPairs(
    const SyntheticSceneOptions& options, const std::set<std::pair<size_t, size_t>>& candidates,
    const std::vector<Rigid3d>& poses, Rng& rng, SceneObservations* seen,
    FeatureDatabase* database) {
  const size_t min_shared =
      options.layout == SyntheticLayout::kUnordered ? options.min_shared_points : 1;
  std::set<std::pair<size_t, size_t>> matched_pairs;
  for (const auto& [i, k] : candidates) {
    const std::vector<FeatureMatch> true_matches =
        SharedObservations(seen->observations[i], seen->observations[k]);
    if (true_matches.size() < min_shared) continue;
    matched_pairs.insert({i, k});
    const uint32_t image_id1 = static_cast<uint32_t>(i + 1);
    const uint32_t image_id2 = static_cast<uint32_t>(k + 1);
    const uint64_t pair_id = ImagePairToPairId(image_id1, image_id2);
    std::vector<FeatureMatch> matches = true_matches;
    // outliers / (inliers + outliers) = outlier_ratio.
    const size_t num_outliers = static_cast<size_t>(
        std::lround(true_matches.size() * options.outlier_ratio / (1.0 - options.outlier_ratio)));
    for (size_t o = 0; o < num_outliers; ++o) {
      const uint32_t idx1 = AddClutterKeypoint(options.camera, rng, &seen->points2D[i]);
      const uint32_t idx2 = AddClutterKeypoint(options.camera, rng, &seen->points2D[k]);
      matches.push_back({idx1, idx2});
    }
    std::shuffle(matches.begin(), matches.end(), rng);
    database->matches[pair_id] = std::move(matches);
    if (true_matches.size() < static_cast<size_t>(std::max(options.min_num_inliers, 1))) continue;
    TwoViewGeometry geometry = MakeGeometry(image_id1, image_id2, poses[k] * poses[i].Inverse(),
                                            CalibrationMatrix(CameraOf(options, i)),
                                            CalibrationMatrix(CameraOf(options, k)));
    geometry.inlier_matches = true_matches;
    database->two_view_geometries[pair_id] = std::move(geometry);
  }
  return matched_pairs;
}

// Two random images (indices), the smaller first; none when both draws are the same image.
std::optional<std::pair<size_t, size_t>> RandomImagePair(size_t num_images, Rng& rng) {
  std::uniform_int_distribution<size_t> random_image(0, num_images - 1);
  const size_t i = random_image(rng);
  const size_t k = random_image(rng);
  if (i == k) return std::nullopt;
  return std::make_pair(std::min(i, k), std::max(i, k));
}

// Whole outlier pairs: random pairs not matched yet, with random matches and a random pose.
void AddOutlierPairs(const SyntheticSceneOptions& options, size_t num_images, Rng& rng,
                     std::set<std::pair<size_t, size_t>>* matched_pairs, SceneObservations* seen,
                     SyntheticScene* scene) {
  FeatureDatabase& database = scene->database;
  const size_t max_pairs = num_images * (num_images - 1) / 2;
  const size_t max_attempts = 100 * static_cast<size_t>(options.num_outlier_pairs) + 100;
  for (size_t attempt = 0;
       attempt < max_attempts &&
       scene->outlier_pair_ids.size() < static_cast<size_t>(options.num_outlier_pairs) &&
       matched_pairs->size() < max_pairs;
       ++attempt) {
    const std::optional<std::pair<size_t, size_t>> drawn = RandomImagePair(num_images, rng);
    if (!drawn || !matched_pairs->insert(*drawn).second) continue;
    const auto [i, k] = *drawn;
    const uint32_t image_id1 = static_cast<uint32_t>(i + 1);
    const uint32_t image_id2 = static_cast<uint32_t>(k + 1);
    const uint64_t pair_id = ImagePairToPairId(image_id1, image_id2);
    std::vector<FeatureMatch> matches;
    for (int o = 0; o < options.num_outlier_pair_matches; ++o) {
      const uint32_t idx1 = AddClutterKeypoint(options.camera, rng, &seen->points2D[i]);
      const uint32_t idx2 = AddClutterKeypoint(options.camera, rng, &seen->points2D[k]);
      matches.push_back({idx1, idx2});
    }
    const Eigen::Quaterniond rotation = RandomRotation(rng);
    const Eigen::Vector3d translation = RandomUnitVector(rng);
    TwoViewGeometry geometry = MakeGeometry(image_id1, image_id2, Rigid3d(rotation, translation),
                                            CalibrationMatrix(CameraOf(options, i)),
                                            CalibrationMatrix(CameraOf(options, k)));
    geometry.inlier_matches = matches;
    database.matches[pair_id] = std::move(matches);
    database.two_view_geometries[pair_id] = std::move(geometry);
    scene->outlier_pair_ids.push_back(pair_id);
  }
}

// The 180 degree turn about the object's vertical axis (y, through the origin) that maps the
// object onto itself when its back looks like its front.
Rigid3d SymmetryTurn() {
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())),
                 Eigen::Vector3d::Zero());
}

// A symmetric pair's two images: a random one, and one whose view turned by the symmetry looks
// from within kSymmetricMaxAngleDeg of it (it sees the twin of what the first sees); none when no
// image does.
std::optional<std::pair<size_t, size_t>> RandomSymmetricPair(const std::vector<Rigid3d>& poses,
                                                             Rng& rng) {
  constexpr double kSymmetricMaxAngleDeg = 25.0;
  std::uniform_int_distribution<size_t> random_image(0, poses.size() - 1);
  const size_t i = random_image(rng);
  const Eigen::Vector3d direction = CameraCenter(poses[i]).normalized();
  std::vector<size_t> twins;
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Vector3d turned = (SymmetryTurn() * CameraCenter(poses[k])).normalized();
    if (k != i && turned.dot(direction) > std::cos(kSymmetricMaxAngleDeg * kDegToRad)) {
      twins.push_back(k);
    }
  }
  if (twins.empty()) return std::nullopt;
  const size_t k = twins[std::uniform_int_distribution<size_t>(0, twins.size() - 1)(rng)];
  return std::make_pair(std::min(i, k), std::max(i, k));
}

// An aliased pair's two images: any two, or on a sequence two at most aliased_max_frame_gap apart
// (repeated facades is seen again from nearby places), or a symmetric pair.
std::optional<std::pair<size_t, size_t>> RandomAliasedPair(const SyntheticSceneOptions& options,
                                                           const std::vector<Rigid3d>& poses,
                                                           Rng& rng) {
  const size_t num_images = poses.size();
  if (options.aliased_symmetric) return RandomSymmetricPair(poses, rng);
  if (options.aliased_max_frame_gap <= 0) return RandomImagePair(num_images, rng);
  std::uniform_int_distribution<size_t> random_image(0, num_images - 1);
  std::uniform_int_distribution<size_t> random_gap(1, options.aliased_max_frame_gap);
  const size_t i = random_image(rng);
  const size_t k = i + random_gap(rng);
  if (k >= num_images) return std::nullopt;
  return std::make_pair(i, k);
}

// The pose an aliased pair's matches obey: the true relative pose turned by a rotation of
// aliased_min_angle_deg to aliased_max_angle_deg about a random axis, and its second camera
// displaced by aliased_shift_m in a random direction (a facade's repeat seen from elsewhere). A
// symmetric pair's second camera is the true one turned by the symmetry: it takes the twins of
// the points it sees for those the first one sees.
Rigid3d AliasedRelativePose(const SyntheticSceneOptions& options, const Rigid3d& cam1_from_world,
                            const Rigid3d& cam2_from_world, Rng& rng) {
  if (options.aliased_symmetric) {
    return cam2_from_world * SymmetryTurn() * cam1_from_world.Inverse();
  }
  const Rigid3d truth = cam2_from_world * cam1_from_world.Inverse();
  const double angle =
      Uniform(rng, options.aliased_min_angle_deg, options.aliased_max_angle_deg) * kDegToRad;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle, RandomUnitVector(rng)));
  return Rigid3d((turn * truth.rotation).normalized(),
                 truth.translation + options.aliased_shift_m * RandomUnitVector(rng));
}

// The points of an aliased pair in the first camera's frame with their keypoints there: distinct
// observations of the image's own scene points when aliased_matches_on_tracks (each wrong match
// then joins that point's track), else new keypoints at random pixels and depths.
std::vector<std::pair<Eigen::Vector3d, uint32_t>> AliasedFirstViews(
    const SyntheticSceneOptions& options, const Rigid3d& pose,
    const std::vector<Eigen::Vector3d>& points, size_t i, Rng& rng, SceneObservations* seen) {
  std::vector<std::pair<Eigen::Vector3d, uint32_t>> views;
  if (options.aliased_matches_on_tracks) {
    std::vector<Observation> observed = seen->observations[i];
    std::shuffle(observed.begin(), observed.end(), rng);
    observed.resize(std::min<size_t>(observed.size(), options.num_aliased_pair_matches));
    for (const Observation& observation : observed) {
      views.emplace_back(pose * points[observation.point_idx], observation.point2D_idx);
    }
    return views;
  }
  const Camera& camera = CameraOf(options, i);
  for (int m = 0; m < options.num_aliased_pair_matches; ++m) {
    Point2D point;
    point.xy = Eigen::Vector2d(Uniform(rng, 0.0, camera.width - 0.01),
                               Uniform(rng, 0.0, camera.height - 0.01));
    seen->points2D[i].push_back(point);
    views.emplace_back(
        Uniform(rng, options.min_depth, options.max_depth) * PixelToBearing(camera, point.xy),
        static_cast<uint32_t>(seen->points2D[i].size() - 1));
  }
  return views;
}

// Aliased pairs: pairs not matched yet whose verified matches obey a wrong relative pose
// (AliasedRelativePose), as repetitive scenes gives.
void AddAliasedPairs(const SyntheticSceneOptions& options, const std::vector<Rigid3d>& poses,
                     const std::vector<Eigen::Vector3d>& points, Rng& rng,
                     std::set<std::pair<size_t, size_t>>* matched_pairs, SceneObservations* seen,
                     SyntheticScene* scene) {
  const size_t num_images = poses.size();
  const size_t wanted = std::max<size_t>(
      options.num_aliased_pairs,
      static_cast<size_t>(std::lround(options.aliased_pair_ratio * matched_pairs->size())));
  const size_t max_pairs = num_images * (num_images - 1) / 2;
  for (size_t attempt = 0;
       attempt < 100 * wanted + 100 && scene->aliased_pair_ids.size() < wanted &&
       matched_pairs->size() < max_pairs;
       ++attempt) {
    const std::optional<std::pair<size_t, size_t>> drawn = RandomAliasedPair(options, poses, rng);
    if (!drawn || matched_pairs->count(*drawn)) continue;
    const auto [i, k] = *drawn;
    const Rigid3d aliased = AliasedRelativePose(options, poses[i], poses[k], rng);
    const Camera& camera1 = CameraOf(options, i);
    const Camera& camera2 = CameraOf(options, k);
    std::vector<FeatureMatch> matches;
    for (const auto& [in_camera1, point2D_idx1] :
         AliasedFirstViews(options, poses[i], points, i, rng, seen)) {
      const Eigen::Vector3d in_camera2 = aliased * in_camera1;
      if (in_camera2.z() <= 0.0 || !in_camera1.allFinite()) continue;
      const Eigen::Vector2d xy2 = ProjectToPixel(camera2, in_camera2) +
                                  Eigen::Vector2d(Gaussian(rng, options.pixel_noise_sigma),
                                                  Gaussian(rng, options.pixel_noise_sigma));
      if (!InsideImage(camera2, xy2)) continue;
      Point2D point2;
      point2.xy = xy2;
      seen->points2D[k].push_back(point2);
      matches.push_back({point2D_idx1, static_cast<uint32_t>(seen->points2D[k].size() - 1)});
    }
    if (matches.size() < static_cast<size_t>(std::max(options.min_num_inliers, 8))) continue;
    matched_pairs->insert({i, k});
    const uint32_t image_id1 = static_cast<uint32_t>(i + 1);
    const uint32_t image_id2 = static_cast<uint32_t>(k + 1);
    const uint64_t pair_id = ImagePairToPairId(image_id1, image_id2);
    TwoViewGeometry geometry = MakeGeometry(image_id1, image_id2, aliased,
                                            CalibrationMatrix(camera1), CalibrationMatrix(camera2));
    geometry.inlier_matches = matches;
    scene->database.matches[pair_id] = std::move(matches);
    scene->database.two_view_geometries[pair_id] = std::move(geometry);
    scene->aliased_pair_ids.push_back(pair_id);
  }
}

// Points seen twice or more become the ground-truth points3D, numbered from 1 in point order.
void AddGroundTruthPoints(const std::vector<Eigen::Vector3d>& points, SceneObservations* seen,
                          Reconstruction* truth) {
  uint64_t next_point3D_id = 1;
  for (size_t j = 0; j < points.size(); ++j) {
    const std::vector<TrackElement>& track = seen->tracks[j];
    if (track.size() < 2) continue;
    const uint64_t point3D_id = next_point3D_id++;
    Point3D point3D;
    point3D.xyz = points[j];
    point3D.color = Eigen::Matrix<uint8_t, 3, 1>(160, 160, 160);
    point3D.error = seen->noise_sum[j] / track.size();
    point3D.track = track;
    for (const TrackElement& element : track) {
      seen->points2D[element.image_id - 1][element.point2D_idx].point3D_id = point3D_id;
    }
    truth->points3D[point3D_id] = std::move(point3D);
  }
}

// An image's keypoints as the database stores them: x, y and, with more columns, a random scale
// and orientation (4) or the affine shape they make (6).
Keypoints StoredKeypoints(const SyntheticSceneOptions& options,
                          const std::vector<Point2D>& points2D, Rng* shape_rng) {
  Keypoints keypoints;
  keypoints.num_cols = options.keypoint_columns;
  keypoints.data.reserve(keypoints.num_cols * points2D.size());
  for (const Point2D& point2D : points2D) {
    keypoints.data.push_back(static_cast<float>(point2D.xy.x()));
    keypoints.data.push_back(static_cast<float>(point2D.xy.y()));
    if (keypoints.num_cols == 2) continue;
    const double scale = Uniform(*shape_rng, 1.5, 12.0);
    const double orientation = Uniform(*shape_rng, -M_PI, M_PI);
    if (keypoints.num_cols == 4) {
      keypoints.data.insert(keypoints.data.end(),
                            {static_cast<float>(scale), static_cast<float>(orientation)});
      continue;
    }
    const double c = scale * std::cos(orientation), s = scale * std::sin(orientation);
    keypoints.data.insert(keypoints.data.end(), {static_cast<float>(c), static_cast<float>(-s),
                                                 static_cast<float>(s), static_cast<float>(c)});
  }
  return keypoints;
}

// Every image: in the database with its keypoints, in the ground truth with its pose.
void AddImages(const SyntheticSceneOptions& options, const std::vector<Rigid3d>& poses,
               SceneObservations* seen, SyntheticScene* scene) {
  // Its own stream, so that the keypoints' shapes leave the rest of the scene as it was.
  Rng shape_rng(options.seed ^ 0x5eed5ba9e5ull);
  const std::vector<std::string> photo_names =
      options.photo_names ? PhotoNames(poses.size(), options.seed) : std::vector<std::string>();
  for (size_t i = 0; i < poses.size(); ++i) {
    const uint32_t image_id = static_cast<uint32_t>(i + 1);
    Image image;
    image.image_id = image_id;
    image.name = options.photo_names ? photo_names[i] : FrameName(i);
    image.camera_id = CameraIdOf(options, i);
    scene->database.images[image_id] = image;

    scene->database.keypoints[image_id] = StoredKeypoints(options, seen->points2D[i], &shape_rng);

    image.cam_from_world = poses[i];
    image.points2D = std::move(seen->points2D[i]);
    scene->ground_truth.images[image_id] = std::move(image);
  }
}

}  // namespace

SyntheticScene BuildSyntheticScene(const SyntheticSceneOptions& options) {
  options.Check();
  Rng rng(options.seed);
  const std::vector<Rigid3d> poses = MakePoses(options, rng);
  const std::vector<Eigen::Vector3d> points = MakePoints(options, poses, rng);
  const size_t num_images = poses.size();
  std::vector<Eigen::Vector3d> centers(num_images);
  for (size_t i = 0; i < num_images; ++i) centers[i] = CameraCenter(poses[i]);
  SceneObservations seen = ObservePoints(options, poses, centers, points, rng);

  SyntheticScene scene;
  for (const size_t i : {size_t{0}, size_t{1}}) {
    if (i >= num_images) break;
    Camera stored_camera = CameraOf(options, i);
    stored_camera.camera_id = CameraIdOf(options, i);
    scene.database.cameras[stored_camera.camera_id] = stored_camera;
  }
  std::set<std::pair<size_t, size_t>> matched_pairs = AddMatchedPairs(
      options, CandidatePairs(options, poses, centers), poses, rng, &seen, &scene.database);
  AddOutlierPairs(options, num_images, rng, &matched_pairs, &seen, &scene);
  AddAliasedPairs(options, poses, points, rng, &matched_pairs, &seen, &scene);
  scene.ground_truth.cameras = scene.database.cameras;
  AddGroundTruthPoints(points, &seen, &scene.ground_truth);
  AddImages(options, poses, &seen, &scene);
  return scene;
}

}  // namespace ramap
