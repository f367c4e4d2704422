#include "ramap/refine/bundle_adjustment.h"

#include <ceres/ceres.h>
#include <ceres/product_manifold.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "ramap/geometry/camera_distortion.h"
#include "ramap/refine/pose_convergence.h"
#include "ramap/refine/reprojection_costs.h"
#include "ramap/util/option_check.h"
#include "ramap/util/parallel.h"
#include "ramap/util/progress_line.h"
#include "ramap/util/run_observer.h"
#include "ramap/util/statistics.h"
#include "ramap/util/timer.h"

namespace ramap {
namespace {

// Between Ceres's iterations: draws the progress line, and ends the iterations when the run's
// observer asks to stop (util/run_observer.h; the caller then throws RunStopped).
class BetweenIterations : public ceres::IterationCallback {
 public:
  explicit BetweenIterations(ProgressLine* line) : line_(line) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    line_->Update(static_cast<size_t>(summary.iteration) + 1);
    try {
      CheckForStop();
    } catch (const RunStopped&) {
      return ceres::SOLVER_ABORT;
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  ProgressLine* line_;
};

// The parameters of `camera` that `options` keeps fixed, by index into COLMAP's order; a guessed
// principal point also where `held_principal_points` names the camera.
std::vector<int> FixedIntrinsics(const BundleAdjustmentOptions& options, const Camera& camera,
                                 const std::set<uint32_t>& held_principal_points = {}) {
  const bool single = HasSingleFocalLength(camera.model);
  const int first_extra = single ? 3 : 4;
  const int num_params = NumCameraParams(camera.model);
  const bool held = HeldAsGiven(options, camera);
  std::vector<int> fixed;
  for (int k = 0; k < num_params; ++k) {
    const bool focal = k < (single ? 1 : 2);
    const bool principal_point = !focal && k < first_extra;
    const bool guessed_principal_point =
        options.refine_guessed_principal_point && options.refine_focal_length &&
        !camera.has_prior_focal_length && held_principal_points.count(camera.camera_id) == 0;
    const bool refined = focal ? options.refine_focal_length && !held
                         : principal_point
                             ? (options.refine_principal_point || guessed_principal_point) && !held
                             : options.refine_extra_params;
    if (!refined) fixed.push_back(k);
  }
  return fixed;
}

// A camera pose prior, in standard deviations per axis: (c - p) / sigma with c = -R^T t, on a
// PoseBlock.
struct PosePriorError {
  PosePriorError(const Eigen::Vector3d& prior_center, const Eigen::Vector3d& std_dev_m)
      : center(prior_center), inverse_std(std_dev_m.cwiseInverse()) {}

  template <typename T>
  bool operator()(const T* const pose, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(pose);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(pose + 4);
    const Eigen::Matrix<T, 3, 1> c = -(q.conjugate() * t);
    for (int k = 0; k < 3; ++k) residual[k] = T(inverse_std[k]) * (c[k] - T(center[k]));
    return true;
  }

  Eigen::Vector3d center;
  Eigen::Vector3d inverse_std;
};

struct Observation {
  uint32_t image_id;
  uint32_t point2D_idx;
  uint64_t point3D_id;
  const Eigen::Vector3d* bearing;
  double focal_px;
  // Pixel residual through the camera model (its intrinsics refined), else on the normalised plane.
  bool in_pixels;
};

// Every track element with a usable bearing (in front of the camera, not grazing).
std::vector<Observation> UsableObservations(const KeypointBearings& bearings,
                                            const std::map<uint32_t, double>& focal_lengths_px,
                                            const Reconstruction& reconstruction,
                                            const BundleAdjustmentOptions& options) {
  const double min_bearing_z = options.min_bearing_z;
  std::vector<Observation> observations;
  for (const auto& [point3D_id, point] : reconstruction.points3D) {
    for (const TrackElement& element : point.track) {
      const auto image = reconstruction.images.find(element.image_id);
      const auto image_bearings = bearings.find(element.image_id);
      if (image == reconstruction.images.end() || image_bearings == bearings.end() ||
          element.point2D_idx >= image_bearings->second.size()) {
        continue;
      }
      const Eigen::Vector3d& bearing = image_bearings->second[element.point2D_idx];
      if (!(bearing.z() >= min_bearing_z)) continue;
      const uint32_t camera_id = image->second.camera_id;
      const auto camera = reconstruction.cameras.find(camera_id);
      const bool in_pixels = camera != reconstruction.cameras.end() &&
                             RefinesIntrinsics(options, camera->second) &&
                             element.point2D_idx < image->second.points2D.size();
      observations.push_back({element.image_id, element.point2D_idx, point3D_id, &bearing,
                              focal_lengths_px.at(camera_id), in_pixels});
    }
  }
  return observations;
}

double SquaredErrorPx(const Observation& o, const Reconstruction& reconstruction) {
  const Image& image = reconstruction.images.at(o.image_id);
  const Eigen::Vector3d x = image.cam_from_world * reconstruction.points3D.at(o.point3D_id).xyz;
  if (x.z() <= 0) return std::numeric_limits<double>::infinity();
  if (o.in_pixels) {
    const Camera& camera = reconstruction.cameras.at(image.camera_id);
    Eigen::Vector2d pixel;
    if (!ProjectPerspective(camera.model, camera.params.data(), x.data(), pixel.data())) {
      return std::numeric_limits<double>::infinity();
    }
    return (pixel - image.points2D[o.point2D_idx].xy).squaredNorm();
  }
  return (o.focal_px * (x.head<2>() / x.z() - o.bearing->head<2>() / o.bearing->z())).squaredNorm();
}

// SquaredErrorPx of every observation, on `num_threads` threads: three lookups in the model's
// maps per observation, done three times per BA (before, to filter, after).
std::vector<double> SquaredErrorsPx(const std::vector<Observation>& observations,
                                    const Reconstruction& reconstruction, int num_threads) {
  std::vector<double> errors(observations.size());
  ForEachShare(observations.size(), NumShares(observations.size(), num_threads, 1),
               [&](size_t, size_t begin, size_t end) {
                 for (size_t k = begin; k < end; ++k)
                   errors[k] = SquaredErrorPx(observations[k], reconstruction);
               });
  return errors;
}

double RmsePx(const std::vector<double>& squared_errors_px) {
  if (squared_errors_px.empty()) return 0.0;
  double sum = 0.0;
  for (const double error : squared_errors_px) sum += error;
  return std::sqrt(sum / squared_errors_px.size());
}

double RmsePx(const std::vector<Observation>& observations, const Reconstruction& reconstruction,
              int num_threads) {
  return RmsePx(SquaredErrorsPx(observations, reconstruction, num_threads));
}

// Each camera in `problem`: the parameters the options keep fixed stay constant (the manifolds
// are kept in `manifolds`, which must outlive the problem).
void HoldFixedIntrinsics(const BundleAdjustmentOptions& options,
                         const std::set<uint32_t>& held_principal_points,
                         Reconstruction* reconstruction, ceres::Problem* problem,
                         std::vector<std::unique_ptr<ceres::SubsetManifold>>* manifolds) {
  for (auto& [camera_id, camera] : reconstruction->cameras) {
    double* params = camera.params.data();
    if (!problem->HasParameterBlock(params)) continue;
    const std::vector<int> fixed = FixedIntrinsics(options, camera, held_principal_points);
    if (fixed.size() == camera.params.size()) {
      problem->SetParameterBlockConstant(params);
    } else if (!fixed.empty()) {
      manifolds->push_back(
          std::make_unique<ceres::SubsetManifold>(static_cast<int>(camera.params.size()), fixed));
      problem->SetManifold(params, manifolds->back().get());
    }
    // A focal length refined from a wrong start (an EXIF value or a crop's) can cross zero in a
    // long step and end negative, which no camera has: it is kept above a field of view of 170
    // degrees across the longest side, far below any start the mapper gives it.
    if (std::find(fixed.begin(), fixed.end(), 0) != fixed.end()) continue;
    const double lowest = 0.05 * static_cast<double>(std::max(camera.width, camera.height));
    if (!(lowest > 0)) continue;
    const int num_focal = HasSingleFocalLength(camera.model) ? 1 : 2;
    for (int k = 0; k < num_focal; ++k)
      problem->SetParameterLowerBound(params, k, std::min(lowest, 0.5 * params[k]));
  }
}

ceres::Solver::Options SolverOptions(const BundleAdjustmentOptions& options,
                                     bool refines_focal_length, size_t num_images) {
  ceres::Solver::Options solver_options;
  solver_options.max_num_iterations = options.max_num_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  if (refines_focal_length) {
    solver_options.max_num_iterations =
        std::max(options.max_num_iterations, options.intrinsics_max_num_iterations);
    solver_options.function_tolerance =
        std::min(options.function_tolerance, options.intrinsics_function_tolerance);
    // A focal length far from its start moves along a narrow valley (it trades off against depth):
    // Levenberg-Marquardt crawls along it. Dogleg steps with non-monotonic acceptance reach the
    // same minimum in fewer, cheaper steps: from COLMAP's guess, the calibration pass and the final
    // BA take much less time for the same focal length and nearly the same accuracy
    // (BENCHMARKS.md, "Same database, unknown intrinsics").
    solver_options.trust_region_strategy_type = ceres::DOGLEG;
    solver_options.use_nonmonotonic_steps = true;
  }
  // Dense Schur is fastest while the reduced camera system is small. Its threads then eliminate
  // points that nearly all touch the same few camera blocks, each update under that block's
  // lock: on two cores one thread solves such a problem faster than two (docs/benchmark-history.md,
  // "Where the seconds of bundle adjustment go").
  const bool dense = num_images <= 50;
  solver_options.linear_solver_type = dense ? ceres::DENSE_SCHUR : ceres::SPARSE_SCHUR;
  solver_options.num_threads = dense ? 1 : options.num_threads;
  solver_options.logging_type = ceres::SILENT;
  return solver_options;
}

// The median depth of each image's observed points, for PoseConvergence.
std::map<uint32_t, double> MedianDepths(const std::vector<Observation>& observations,
                                        const Reconstruction& reconstruction) {
  std::map<uint32_t, std::vector<double>> depths;
  for (const Observation& o : observations) {
    const Rigid3d& pose = reconstruction.images.at(o.image_id).cam_from_world;
    depths[o.image_id].push_back((pose * reconstruction.points3D.at(o.point3D_id).xyz).z());
  }
  std::map<uint32_t, double> medians;
  for (auto& [image_id, values] : depths) medians[image_id] = Median(std::move(values));
  return medians;
}

// The intrinsics `problem` refines, for PoseConvergence.
std::vector<RefinedIntrinsics> RefinedIntrinsicsIn(const ceres::Problem& problem,
                                                   const BundleAdjustmentOptions& options,
                                                   const Reconstruction& reconstruction) {
  std::vector<RefinedIntrinsics> refined;
  for (const auto& [camera_id, camera] : reconstruction.cameras) {
    if (!problem.HasParameterBlock(camera.params.data()) || !RefinesIntrinsics(options, camera))
      continue;
    refined.push_back({camera.params.data(), HasSingleFocalLength(camera.model) ? 1 : 2});
  }
  return refined;
}

// The coordinate-wise median of the points `observations` see: a point among them.
Eigen::Vector3d MedianObservedPoint(const std::vector<Observation>& observations,
                                    const Reconstruction& reconstruction) {
  if (observations.empty()) return Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> points;
  points.reserve(observations.size());
  for (const Observation& o : observations)
    points.push_back(reconstruction.points3D.at(o.point3D_id).xyz);
  return MedianPoint(points);
}

// Ceres solves with the world's origin among the points, not at the first camera where averaging
// put it. A camera's translation (cam_from_world) is its rotation times its offset from the
// origin: a camera that turns about a point far from the origin moves its translation along an
// arc, which Gauss-Newton follows in short steps. About the origin it moves its rotation alone.
// Every camera circling the scene does so when a focal length moves far (a turntable from
// COLMAP's guess, half the true value: every angle between views doubles). The reconstruction
// returns to its own frame when this goes out of scope.
class WorldOriginAmongThePoints {
 public:
  WorldOriginAmongThePoints(const std::vector<Observation>& observations,
                            Reconstruction* reconstruction)
      : origin_(MedianObservedPoint(observations, *reconstruction)),
        reconstruction_(reconstruction) {
    Move(origin_);
  }
  ~WorldOriginAmongThePoints() { Move(-origin_); }
  WorldOriginAmongThePoints(const WorldOriginAmongThePoints&) = delete;
  WorldOriginAmongThePoints& operator=(const WorldOriginAmongThePoints&) = delete;

  // `priors` in the moved frame.
  std::map<uint32_t, PosePrior> Moved(std::map<uint32_t, PosePrior> priors) const {
    for (auto& [image_id, prior] : priors) prior.center -= origin_;
    return priors;
  }

 private:
  // The origin to `origin` (in the current frame); points and cameras stay where they are.
  void Move(const Eigen::Vector3d& origin) {
    for (auto& [point_id, point] : reconstruction_->points3D) point.xyz -= origin;
    for (auto& [image_id, image] : reconstruction_->images)
      image.cam_from_world.translation += image.cam_from_world.rotation * origin;
  }

  Eigen::Vector3d origin_;
  Reconstruction* reconstruction_;
};

// The pose priors' residuals on `poses`, which get the pose manifold; the first pose is held fixed
// (gauge) unless three or more priors fix the frame.
void AddPriorsAndGauge(const std::map<uint32_t, PosePrior>& priors, ceres::LossFunction* prior_loss,
                       ceres::Manifold* pose_manifold, std::map<uint32_t, PoseBlock>* poses,
                       ceres::Problem* problem) {
  int num_priors = 0;
  for (const auto& [image_id, prior] : priors) {
    const auto pose = poses->find(image_id);
    if (pose == poses->end()) continue;
    problem->AddResidualBlock(new ceres::AutoDiffCostFunction<PosePriorError, 3, 7>(
                                  new PosePriorError(prior.center, prior.std_dev_m)),
                              prior_loss, pose->second.data());
    ++num_priors;
  }
  bool gauge_fixed = num_priors >= 3;
  for (auto& [image_id, pose] : *poses) {
    problem->SetManifold(pose.data(), pose_manifold);
    if (!gauge_fixed) {
      problem->SetParameterBlockConstant(pose.data());
      gauge_fixed = true;
    }
  }
}

// One Ceres solve over `observations`; the first image observed is held fixed (gauge) unless
// three or more pose priors fix it.
ceres::Solver::Summary Solve(const std::vector<Observation>& observations,
                             const std::map<uint32_t, PosePrior>& priors,
                             const BundleAdjustmentOptions& options,
                             const std::set<uint32_t>& held_principal_points,
                             const std::map<uint32_t, uint32_t>& shared,
                             Reconstruction* reconstruction, std::ostream* progress,
                             const std::string& what) {
  const WorldOriginAmongThePoints origin(observations, reconstruction);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  std::vector<std::unique_ptr<ceres::SubsetManifold>> intrinsics_manifolds;  // outlive `problem`
  ceres::Problem problem(problem_options);
  ceres::CauchyLoss loss(options.loss_scale_px);
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> pose_manifold;
  std::map<uint32_t, PoseBlock> poses;  // of the images observed
  const auto pose_block = [&](uint32_t image_id) {
    auto [it, added] = poses.try_emplace(image_id);
    if (added) {
      const Rigid3d& pose = reconstruction->images.at(image_id).cam_from_world;
      it->second << pose.rotation.coeffs(), pose.translation;
    }
    return it->second.data();
  };
  for (const Observation& o : observations) {
    const Image& image = reconstruction->images.at(o.image_id);
    double* pose = pose_block(o.image_id);
    double* point = reconstruction->points3D.at(o.point3D_id).xyz.data();
    if (o.in_pixels) {
      Camera& camera = reconstruction->cameras.at(shared.at(image.camera_id));
      problem.AddResidualBlock(NewPixelCost(camera.model, image.points2D[o.point2D_idx].xy), &loss,
                               pose, point, camera.params.data());
      continue;
    }
    problem.AddResidualBlock(NewNormalizedPlaneCost(*o.bearing, o.focal_px), &loss, pose, point);
  }
  HoldFixedIntrinsics(options, held_principal_points, reconstruction, &problem,
                      &intrinsics_manifolds);
  ceres::HuberLoss prior_loss(1.0);
  AddPriorsAndGauge(origin.Moved(priors), &prior_loss, &pose_manifold, &poses, &problem);
  // The slow valley is the focal length's: distortion alone converges at the ordinary tolerance.
  const bool refines_focal_length = std::any_of(
      reconstruction->cameras.begin(), reconstruction->cameras.end(), [&](const auto& entry) {
        return problem.HasParameterBlock(entry.second.params.data()) &&
               RefinesFocalLength(options, entry.second);
      });
  ceres::Solver::Options solver_options =
      SolverOptions(options, refines_focal_length, reconstruction->images.size());
  ProgressLine line(progress, what, static_cast<size_t>(solver_options.max_num_iterations),
                    "iterations");
  line.SetTotalIsALimit();
  BetweenIterations between(&line);
  solver_options.callbacks.push_back(&between);
  std::optional<PoseConvergence> still;
  if (options.pose_tolerance_deg > 0) {
    // With the intrinsics alone watched, the poses' depths are not needed.
    const bool intrinsics_only = options.settle_intrinsics_only && refines_focal_length;
    still.emplace(intrinsics_only ? nullptr : &poses,
                  intrinsics_only ? std::map<uint32_t, double>()
                                  : MedianDepths(observations, *reconstruction),
                  RefinedIntrinsicsIn(problem, options, *reconstruction),
                  options.pose_tolerance_deg, solver_options.initial_trust_region_radius);
    solver_options.update_state_every_iteration = true;
    solver_options.callbacks.push_back(&*still);
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  line.Finish(summary.iterations.size(), summary.termination_type != ceres::USER_FAILURE);
  CheckForStop();
  for (const auto& [image_id, pose] : poses) {
    Rigid3d& cam_from_world = reconstruction->images.at(image_id).cam_from_world;
    cam_from_world.rotation.coeffs() = pose.head<4>();
    cam_from_world.rotation.normalize();
    cam_from_world.translation = pose.tail<3>();
  }
  for (auto& [camera_id, camera] : reconstruction->cameras)
    camera.params = reconstruction->cameras.at(shared.at(camera_id)).params;
  return summary;
}

// The first solve's loss scale when the median start error (of `errors`, squared, in pixels)
// exceeds loss_scale_px (wide_start_loss_factor times that median), else 0.
double WideStartLossPx(std::vector<double> errors, const BundleAdjustmentOptions& options) {
  if (options.wide_start_loss_factor <= 0 || errors.empty()) return 0.0;
  const auto middle = errors.begin() + errors.size() / 2;
  std::nth_element(errors.begin(), middle, errors.end());
  const double median_px = std::sqrt(*middle);
  return median_px > options.loss_scale_px ? options.wide_start_loss_factor * median_px : 0.0;
}

// Detaches observations whose error exceeds the bound (counted per image in `per_image`), removes
// points left with fewer than two observations, and returns the number of observations detached.
int FilterObservations(const std::vector<Observation>& observations, double max_error_px,
                       int num_threads, Reconstruction* reconstruction,
                       std::map<uint32_t, int>* per_image) {
  const std::vector<double> errors = SquaredErrorsPx(observations, *reconstruction, num_threads);
  std::map<uint64_t, std::vector<TrackElement>> kept;
  int num_filtered = 0;
  for (size_t k = 0; k < observations.size(); ++k) {
    const Observation& o = observations[k];
    if (errors[k] <= max_error_px * max_error_px) {
      kept[o.point3D_id].push_back({o.image_id, o.point2D_idx});
    } else {
      ++num_filtered;
      ++(*per_image)[o.image_id];
    }
  }
  for (auto it = reconstruction->points3D.begin(); it != reconstruction->points3D.end();) {
    const auto track = kept.find(it->first);
    const bool survives = track != kept.end() && track->second.size() >= 2;
    for (const TrackElement& element : it->second.track) {
      const bool still_observed =
          survives &&
          std::any_of(track->second.begin(), track->second.end(), [&](const TrackElement& e) {
            return e.image_id == element.image_id && e.point2D_idx == element.point2D_idx;
          });
      auto image = reconstruction->images.find(element.image_id);
      if (!still_observed && image != reconstruction->images.end() &&
          element.point2D_idx < image->second.points2D.size()) {
        image->second.points2D[element.point2D_idx].point3D_id = kInvalidPoint3DId;
      }
    }
    if (survives) {
      it->second.track = track->second;
      ++it;
    } else {
      it = reconstruction->points3D.erase(it);
    }
  }
  return num_filtered;
}

// `track` thinned to at most `max_count` observations spread evenly over its images in id order
// (a sequence's frame order), the first and last kept, so the point keeps its widest baseline
// (0: all).
std::vector<TrackElement> ThinnedTrack(std::vector<TrackElement> track, int max_count) {
  if (max_count <= 0 || static_cast<int>(track.size()) <= max_count) return track;
  std::sort(track.begin(), track.end(),
            [](const TrackElement& a, const TrackElement& b) { return a.image_id < b.image_id; });
  std::vector<TrackElement> thinned;
  const double step = static_cast<double>(track.size() - 1) / (max_count - 1);
  for (int i = 0; i < max_count; ++i) {
    thinned.push_back(track[static_cast<size_t>(std::lround(i * step))]);
  }
  return thinned;
}

}  // namespace

void BundleAdjustmentOptions::Check() const {
  CheckOptionValues(BundleAdjustmentOptionTable(), *this);
  // The settings no command line option reaches.
  const std::string s = "BundleAdjustmentOptions::";
  CheckOption(min_bearing_z > 0 && min_bearing_z < 1, s + "min_bearing_z", "in (0, 1)",
              min_bearing_z);
  CheckOption(num_threads >= 1, s + "num_threads", ">= 1", num_threads);
  CheckOption(min_observations_per_image >= 0, s + "min_observations_per_image", ">= 0",
              min_observations_per_image);
  CheckOption(intrinsics_function_tolerance >= 0, s + "intrinsics_function_tolerance", ">= 0",
              intrinsics_function_tolerance);
  CheckOption(intrinsics_max_num_iterations >= 0, s + "intrinsics_max_num_iterations", ">= 0",
              intrinsics_max_num_iterations);
}

BundleAdjustmentOptions PointSubsetOptions(BundleAdjustmentOptions options, int max_num_points) {
  options.max_num_points = max_num_points;
  options.min_observations_per_image = std::min(options.min_observations_per_image, 50);
  options.max_observations_per_point = 0;
  return options;
}

BundleAdjustmentOptions PastTheFocalValley(BundleAdjustmentOptions options) {
  options.intrinsics_function_tolerance =
      std::max(options.intrinsics_function_tolerance, options.function_tolerance);
  return options;
}

bool HeldAsGiven(const BundleAdjustmentOptions& options, const Camera& camera) {
  return options.keep_prior_intrinsics && camera.has_prior_focal_length &&
         options.disproved_given_cameras.count(camera.camera_id) == 0;
}

bool RefinesIntrinsics(const BundleAdjustmentOptions& options, const Camera& camera) {
  const bool any =
      options.refine_focal_length || options.refine_principal_point || options.refine_extra_params;
  switch (camera.model) {
    case CameraModel::kSimplePinhole:
    case CameraModel::kPinhole:
    case CameraModel::kSimpleRadial:
    case CameraModel::kRadial:
    case CameraModel::kOpenCV:
    case CameraModel::kFullOpenCV:
      return any && static_cast<int>(FixedIntrinsics(options, camera).size()) <
                        NumCameraParams(camera.model);
    default:
      return false;
  }
}

bool RefinesFocalLength(const BundleAdjustmentOptions& options, const Camera& camera) {
  if (!RefinesIntrinsics(options, camera)) return false;
  const std::vector<int> fixed = FixedIntrinsics(options, camera);
  return fixed.empty() || fixed.front() != 0;
}

std::map<uint32_t, uint32_t> SharedIntrinsics(const BundleAdjustmentOptions& options,
                                              const Reconstruction& reconstruction) {
  if (options.share_identical_intrinsics) return IdenticalCameras(reconstruction.cameras);
  std::map<uint32_t, uint32_t> own;
  for (const auto& [camera_id, camera] : reconstruction.cameras) own[camera_id] = camera_id;
  return own;
}

Reconstruction PointsForBundleAdjustment(const Reconstruction& reconstruction,
                                         const BundleAdjustmentOptions& options) {
  options.Check();
  const bool all_points =
      options.min_track_length <= 2 &&
      (options.max_num_points == 0 ||
       static_cast<int>(reconstruction.points3D.size()) <= options.max_num_points);
  const size_t budget =
      options.max_num_points == 0 ? reconstruction.points3D.size() : options.max_num_points;
  std::map<uint64_t, std::vector<TrackElement>> chosen;  // point id -> the observations adjusted
  // (track length, point id), longest first: the lengths read once rather than in every
  // comparison, which made the sort a large share of a subset's set-up.
  std::vector<std::pair<size_t, uint64_t>> by_length;
  by_length.reserve(reconstruction.points3D.size());
  for (const auto& [id, point] : reconstruction.points3D)
    by_length.emplace_back(point.track.size(), id);
  // Within the budget every point is taken, in any order, and no image's count matters.
  if (!all_points) {
    std::stable_sort(by_length.begin(), by_length.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
  }
  std::map<uint32_t, int> per_image;
  for (const auto& [length, id] : by_length) {
    std::vector<TrackElement> track =
        ThinnedTrack(reconstruction.points3D.at(id).track, options.max_observations_per_point);
    if (!all_points) {
      // Past the budget, or seen in too few images, a point is taken only while one of its
      // images has too few observations. Short tracks come last and do not count: an image
      // the longer tracks leave short keeps all of its own.
      const bool short_track = static_cast<int>(length) < options.min_track_length;
      if ((chosen.size() >= budget || short_track) &&
          std::none_of(track.begin(), track.end(), [&](const TrackElement& e) {
            return per_image[e.image_id] < options.min_observations_per_image;
          })) {
        continue;
      }
      if (!short_track)
        for (const TrackElement& e : track) ++per_image[e.image_id];
    }
    chosen.emplace(id, std::move(track));
  }
  Reconstruction subset = reconstruction;
  for (auto& [image_id, image] : subset.images) {
    for (Point2D& point : image.points2D) point.point3D_id = kInvalidPoint3DId;
  }
  for (auto it = subset.points3D.begin(); it != subset.points3D.end();) {
    const auto kept = chosen.find(it->first);
    if (kept == chosen.end()) {
      it = subset.points3D.erase(it);
      continue;
    }
    it->second.track = kept->second;
    for (const TrackElement& e : kept->second) {
      const auto image = subset.images.find(e.image_id);
      if (image != subset.images.end() && e.point2D_idx < image->second.points2D.size()) {
        image->second.points2D[e.point2D_idx].point3D_id = it->first;
      }
    }
    ++it;
  }
  return subset;
}

namespace {

// BundleAdjust without the check of the principal points, those of `held_principal_points`'s
// cameras held.
BundleAdjustmentSummary Adjust(const KeypointBearings& bearings,
                               const std::map<uint32_t, double>& focal_lengths_px,
                               Reconstruction* reconstruction,
                               const BundleAdjustmentOptions& options,
                               const std::set<uint32_t>& held_principal_points,
                               const std::map<uint32_t, PosePrior>& priors,
                               std::ostream* progress) {
  Timer timer;
  BundleAdjustmentSummary summary;
  for (const auto& [image_id, prior] : priors)
    summary.num_priors += reconstruction->images.count(image_id);
  summary.num_images = static_cast<int>(reconstruction->images.size());
  std::vector<Observation> observations =
      UsableObservations(bearings, focal_lengths_px, *reconstruction, options);
  summary.num_observations = static_cast<int>(observations.size());
  const std::vector<double> start_errors =
      SquaredErrorsPx(observations, *reconstruction, options.num_threads);
  summary.initial_rmse_px = RmsePx(start_errors);
  const std::map<uint32_t, uint32_t> shared = SharedIntrinsics(options, *reconstruction);
  // Solve, detach what still disagrees, and solve once more without it when it is much of the
  // data (min_filtered_fraction_to_solve_again; COLMAP's global BA always does).
  summary.wide_start_loss_px = WideStartLossPx(start_errors, options);
  for (int round = 0; round < 2 && !observations.empty(); ++round) {
    const bool wide = round == 0 && summary.wide_start_loss_px > 0;
    BundleAdjustmentOptions solve_options = options;
    if (wide) solve_options.loss_scale_px = summary.wide_start_loss_px;
    const ceres::Solver::Summary solve =
        Solve(observations, priors, solve_options, held_principal_points, shared, reconstruction,
              progress,
              wide         ? "bundle adjustment under a wide loss"
              : round == 0 ? "bundle adjustment"
                           : "bundle adjustment without the outliers");
    summary.num_iterations += static_cast<int>(solve.iterations.size());
    ++summary.num_solves;
    // USER_SUCCESS: PoseConvergence ended the solve (the progress callback only aborts).
    summary.poses_settled = solve.termination_type == ceres::USER_SUCCESS;
    summary.converged = solve.termination_type == ceres::CONVERGENCE || summary.poses_settled;
    const int filtered =
        FilterObservations(observations, options.max_reprojection_error_px, options.num_threads,
                           reconstruction, &summary.filtered_per_image);
    summary.num_filtered_observations += filtered;
    const double filtered_fraction = static_cast<double>(filtered) / observations.size();
    observations = UsableObservations(bearings, focal_lengths_px, *reconstruction, options);
    if (!wide &&
        (filtered == 0 || filtered_fraction < options.min_filtered_fraction_to_solve_again)) {
      break;
    }
  }
  summary.final_rmse_px = RmsePx(observations, *reconstruction, options.num_threads);
  summary.num_points = static_cast<int>(reconstruction->points3D.size());
  summary.seconds = timer.ElapsedSeconds();
  return summary;
}

// Whether `options` refine the guessed principal point of some camera of `reconstruction`.
bool RefinesGuessedPrincipalPoint(const BundleAdjustmentOptions& options,
                                  const Reconstruction& reconstruction) {
  if (!options.refine_guessed_principal_point || options.refine_principal_point) return false;
  BundleAdjustmentOptions held = options;
  held.refine_guessed_principal_point = false;
  return std::any_of(reconstruction.cameras.begin(), reconstruction.cameras.end(),
                     [&](const auto& entry) {
                       return FixedIntrinsics(options, entry.second).size() <
                              FixedIntrinsics(held, entry.second).size();
                     });
}

// The cameras whose principal point moved from `start` by more than max_principal_point_shift.
std::vector<uint32_t> DriftedPrincipalPoints(const std::map<uint32_t, Camera>& start,
                                             const Reconstruction& reconstruction,
                                             const BundleAdjustmentOptions& options) {
  std::vector<uint32_t> drifted;
  for (const auto& [camera_id, camera] : reconstruction.cameras) {
    const Camera& before = start.at(camera_id);
    const int first = HasSingleFocalLength(camera.model) ? 1 : 2;
    const double shift_x = std::abs(camera.params[first] - before.params[first]);
    const double shift_y = std::abs(camera.params[first + 1] - before.params[first + 1]);
    if (shift_x > options.max_principal_point_shift * camera.width ||
        shift_y > options.max_principal_point_shift * camera.height) {
      drifted.push_back(camera_id);
    }
  }
  return drifted;
}

// The median reprojection error of each camera's observations in `reconstruction`, pixels.
std::map<uint32_t, double> MedianErrorPerCameraPx(
    const KeypointBearings& bearings, const std::map<uint32_t, double>& focal_lengths_px,
    const Reconstruction& reconstruction, const BundleAdjustmentOptions& options) {
  const std::vector<Observation> observations =
      UsableObservations(bearings, focal_lengths_px, reconstruction, options);
  const std::vector<double> errors =
      SquaredErrorsPx(observations, reconstruction, options.num_threads);
  std::map<uint32_t, std::vector<double>> per_camera;
  for (size_t k = 0; k < observations.size(); ++k) {
    per_camera[reconstruction.images.at(observations[k].image_id).camera_id].push_back(errors[k]);
  }
  std::map<uint32_t, double> medians;
  for (auto& [camera_id, camera_errors] : per_camera)
    medians[camera_id] = std::sqrt(Median(std::move(camera_errors)));
  return medians;
}

// Of the cameras in `moved`, those whose principal point in `free_model` lies inside the image and
// whose median reprojection error there is min_principal_point_error_decrease below that in
// `held_model`, where it was held.
std::vector<uint32_t> ConfirmedPrincipalPoints(const std::vector<uint32_t>& moved,
                                               const Reconstruction& free_model,
                                               const Reconstruction& held_model,
                                               const KeypointBearings& bearings,
                                               const std::map<uint32_t, double>& focal_lengths_px,
                                               const BundleAdjustmentOptions& options) {
  const std::map<uint32_t, double> free_errors =
      MedianErrorPerCameraPx(bearings, focal_lengths_px, free_model, options);
  const std::map<uint32_t, double> held_errors =
      MedianErrorPerCameraPx(bearings, focal_lengths_px, held_model, options);
  std::vector<uint32_t> confirmed;
  for (const uint32_t camera_id : moved) {
    const Camera& camera = free_model.cameras.at(camera_id);
    const int first = HasSingleFocalLength(camera.model) ? 1 : 2;
    const double x = camera.params[first];
    const double y = camera.params[first + 1];
    const bool inside = x >= 0 && x <= camera.width && y >= 0 && y <= camera.height;
    const auto free_error = free_errors.find(camera_id);
    const auto held_error = held_errors.find(camera_id);
    if (inside && free_error != free_errors.end() && held_error != held_errors.end() &&
        free_error->second <
            (1.0 - options.min_principal_point_error_decrease) * held_error->second) {
      confirmed.push_back(camera_id);
    }
  }
  return confirmed;
}

}  // namespace

BundleAdjustmentSummary BundleAdjust(const KeypointBearings& bearings,
                                     const std::map<uint32_t, double>& focal_lengths_px,
                                     Reconstruction* reconstruction,
                                     const BundleAdjustmentOptions& options,
                                     const std::map<uint32_t, PosePrior>& priors,
                                     std::ostream* progress) {
  options.Check();
  if (!RefinesGuessedPrincipalPoint(options, *reconstruction))
    return Adjust(bearings, focal_lengths_px, reconstruction, options, {}, priors, progress);
  const Reconstruction start = *reconstruction;
  BundleAdjustmentSummary summary =
      Adjust(bearings, focal_lengths_px, reconstruction, options, {}, priors, progress);
  const std::vector<uint32_t> moved =
      DriftedPrincipalPoints(start.cameras, *reconstruction, options);
  if (moved.empty()) return summary;
  // Solved again from the start with the far-moved ones held: where one drifted, the poses
  // followed it, so the held solve is not the free one with the principal point put back.
  Reconstruction free_model = std::move(*reconstruction);
  *reconstruction = start;
  const BundleAdjustmentSummary held = Adjust(bearings, focal_lengths_px, reconstruction, options,
                                              {moved.begin(), moved.end()}, priors, progress);
  const std::vector<uint32_t> confirmed = ConfirmedPrincipalPoints(
      moved, free_model, *reconstruction, bearings, focal_lengths_px, options);
  double seconds = summary.seconds + held.seconds;
  int num_iterations = summary.num_iterations + held.num_iterations;
  std::set<uint32_t> unconfirmed(moved.begin(), moved.end());
  for (const uint32_t camera_id : confirmed) unconfirmed.erase(camera_id);
  BundleAdjustmentSummary result = held;
  if (unconfirmed.empty()) {
    *reconstruction = std::move(free_model);
    result = summary;
  } else if (!confirmed.empty()) {
    *reconstruction = start;
    result =
        Adjust(bearings, focal_lengths_px, reconstruction, options, unconfirmed, priors, progress);
    seconds += result.seconds;
    num_iterations += result.num_iterations;
  }
  result.seconds = seconds;
  result.num_iterations = num_iterations;
  result.principal_points_confirmed = confirmed;
  result.principal_points_drifted.assign(unconfirmed.begin(), unconfirmed.end());
  return result;
}

}  // namespace ramap
