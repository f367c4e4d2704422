#include "ramap/graph/loop_candidates.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "ramap/geometry/rotation.h"
#include "ramap/scene/features.h"
#include "ramap/util/error.h"
#include "ramap/util/statistics.h"

namespace ramap {

void LoopCandidateOptions::Check() const { CheckOptionValues(LoopCandidateOptionTable(), *this); }

std::vector<LoopCandidate> FindLoopCandidates(const Reconstruction& reconstruction,
                                              const std::vector<uint32_t>& capture_order,
                                              const std::set<uint64_t>& matched_pair_ids,
                                              const LoopCandidateOptions& options) {
  options.Check();
  struct View {
    uint32_t id;
    int frame;
    Eigen::Vector3d center, axis;
  };
  std::vector<View> views;
  for (size_t k = 0; k < capture_order.size(); ++k) {
    const auto image = reconstruction.images.find(capture_order[k]);
    if (image == reconstruction.images.end()) continue;
    const Rigid3d& pose = image->second.cam_from_world;
    views.push_back({capture_order[k], static_cast<int>(k), CameraCenter(pose),
                     pose.rotation.conjugate() * Eigen::Vector3d::UnitZ()});
  }
  std::vector<double> steps;
  for (size_t k = 1; k < views.size(); ++k) {
    steps.push_back((views[k].center - views[k - 1].center).norm());
  }
  std::vector<LoopCandidate> candidates;
  if (steps.empty()) return candidates;
  const double baseline = Median(steps);
  if (!(baseline > 0)) return candidates;  // not moving: nothing is a revisit
  const double max_distance = options.max_distance_baselines * baseline;
  const double min_cos = std::cos(options.max_view_angle_deg * kDegToRad);
  // Quadratic in the registered images, cheap next to matching even one pair for a few thousand.
  for (size_t a = 0; a < views.size(); ++a) {
    for (size_t b = a + 1; b < views.size(); ++b) {
      if (views[b].frame - views[a].frame < options.min_frame_gap) continue;
      const double distance = (views[a].center - views[b].center).norm();
      const double cos_angle = views[a].axis.dot(views[b].axis);
      if (distance > max_distance || cos_angle < min_cos) continue;
      const uint32_t id1 = std::min(views[a].id, views[b].id);
      const uint32_t id2 = std::max(views[a].id, views[b].id);
      if (matched_pair_ids.count(ImagePairToPairId(id1, id2))) continue;
      candidates.push_back(
          {id1, id2, distance / baseline, std::acos(std::clamp(cos_angle, -1.0, 1.0)) * kRadToDeg});
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const LoopCandidate& x, const LoopCandidate& y) {
              return x.distance_baselines < y.distance_baselines;
            });
  std::map<uint32_t, int> per_image;
  std::vector<LoopCandidate> kept;
  for (const LoopCandidate& candidate : candidates) {
    if (per_image[candidate.image_id1] >= options.max_candidates_per_image ||
        per_image[candidate.image_id2] >= options.max_candidates_per_image) {
      continue;
    }
    ++per_image[candidate.image_id1];
    ++per_image[candidate.image_id2];
    kept.push_back(candidate);
  }
  return kept;
}

}  // namespace ramap
