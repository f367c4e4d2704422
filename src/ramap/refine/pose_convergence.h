// A stopping rule for bundle adjustment that looks at what the mapper returns: the poses. Ceres
// stops when an iteration lowers the cost by less than a fraction (function_tolerance), but that
// cost is mostly the points': on a small, well-connected scene the poses stop moving after a few
// iterations while thousands of points go on settling and the cost keeps falling. Those points are
// triangulated again after BA anyway. This callback ends the solve once two successive accepted
// steps each moved every camera by less than a tolerance, measured as angles: its rotation, its
// centre's displacement as seen from its points (displacement over their median depth), and its
// refined focal length and principal point (relative change). A step counts only when the trust
// region did not bound it: after rejected steps the region shrinks, and so do the steps, near a
// minimum or not. It did not when the region is at least its initial size, or when a dogleg step
// that its model predicted well (ratio above 0.75) left the region as it was: Ceres then grows a
// region the step reached to three times the step, so the step lay well inside it. A long chain
// whose poses still drift, and a focal length crawling along its valley, keep iterating to Ceres's
// own tolerance. A solve kept only for its intrinsics (a calibration on a subset of the points)
// can end once they alone have settled.
#pragma once

#include <ceres/iteration_callback.h>

#include <cstdint>
#include <map>
#include <vector>

#include "ramap/refine/reprojection_costs.h"

namespace ramap {

// The intrinsics a solve refines: the camera's parameter array, and how many of its leading
// entries are focal lengths (1 or 2) and principal point (2); distortion is left out, since it
// moves with the focal length.
struct RefinedIntrinsics {
  const double* params = nullptr;
  int num_focal_lengths = 1;
};

class PoseConvergence : public ceres::IterationCallback {
 public:
  // `poses` are Ceres's parameter blocks (kept up to date every iteration:
  // Solver::Options::update_state_every_iteration), or null where only the intrinsics count (a
  // solve that is kept for its intrinsics alone); `median_depths` the median depth of each
  // image's observed points at the start, in the poses' units; `min_trust_region_radius` the
  // solve's initial trust region radius.
  PoseConvergence(const std::map<uint32_t, PoseBlock>* poses,
                  std::map<uint32_t, double> median_depths,
                  std::vector<RefinedIntrinsics> intrinsics, double tolerance_deg,
                  double min_trust_region_radius);

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;

  // Whether the solve ended here rather than at Ceres's own criteria.
  bool stopped() const { return stopped_; }

 private:
  // The largest angle any camera moved by since the last accepted step, in degrees.
  double LargestMotionDeg() const;
  // The largest relative change of a refined focal length or principal point, in radians.
  double IntrinsicsMotionRad() const;
  void Remember();

  const std::map<uint32_t, PoseBlock>* poses_;
  std::map<uint32_t, double> median_depths_;
  std::vector<RefinedIntrinsics> intrinsics_;
  double tolerance_deg_;
  double min_trust_region_radius_;
  double last_trust_region_radius_ = 0.0;  // after the previous iteration, rejected or not
  std::map<uint32_t, PoseBlock> last_poses_;
  std::vector<std::vector<double>> last_intrinsics_;
  int num_still_steps_ = 0;
  bool stopped_ = false;
};

}  // namespace ramap
