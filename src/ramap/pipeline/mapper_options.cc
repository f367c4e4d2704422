#include "ramap/pipeline/mapper_options.h"

#include <string>

#include "ramap/util/error.h"
#include "ramap/util/option_check.h"

namespace ramap {

void MapperOptions::Check() const {
  view_graph_calibration.Check();
  relative_pose.Check();
  if (!pose_graph.Check()) {
    throw InputError("--PoseGraph.keyframe_interval",
                     "must be >= 1, got " + std::to_string(pose_graph.keyframe_interval));
  }
  const std::string rotation_problem = rotation_averaging.Problem();
  if (!rotation_problem.empty()) throw InputError("--RotationAveraging", rotation_problem);
  pair_direction.Check();
  translation_averaging.Check();
  structure.Check();
  bundle_adjustment.Check();
  if (min_component_size < 2) {
    throw InputError("--Mapper.min_component_size",
                     "must be >= 2, got " + std::to_string(min_component_size));
  }
  if (num_threads < 1) {
    throw InputError("--Mapper.num_threads", "must be >= 1, got " + std::to_string(num_threads));
  }
  if (!(max_focal_change_in_bundle_adjustment >= 0)) {
    throw InputError("--Mapper.max_focal_change_in_bundle_adjustment", "must be >= 0");
  }
  CheckOption(calibration_num_points >= 0, "--Mapper.calibration_num_points", ">= 0",
              calibration_num_points);
}

}  // namespace ramap
