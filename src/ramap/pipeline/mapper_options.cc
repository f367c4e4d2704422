#include "ramap/pipeline/mapper_options.h"

#include <string>

#include "ramap/util/error.h"
#include "ramap/util/option_check.h"

namespace ramap {

void MapperOptions::Check() const {
  view_graph_calibration.Check();
  relative_pose.Check();
  pose_graph.Check();
  rotation_averaging.Check();
  pair_direction.Check();
  direction_consistency.Check();
  translation_averaging.Check();
  translation_windows.Check();
  structure.Check();
  reregistration.Check();
  bundle_adjustment.Check();
  given_intrinsics_test.Check();
  CheckOption(min_component_size >= 2, "--Mapper.min_component_size", ">= 2", min_component_size);
  CheckOption(num_threads >= 1, "--Mapper.num_threads", ">= 1", num_threads);
  CheckOption(max_focal_change_in_bundle_adjustment >= 0,
              "--Mapper.max_focal_change_in_bundle_adjustment", ">= 0",
              max_focal_change_in_bundle_adjustment);
  CheckOption(num_refinement_rounds >= 1, "--BundleAdjustment.num_rounds", ">= 1",
              num_refinement_rounds);
  CheckOption(calibration_num_points >= 0, "--Mapper.calibration_num_points", ">= 0",
              calibration_num_points);
}

}  // namespace ramap
