#include "ramap/mapper/mapper_options.h"

namespace ramap {

// The mapper's own options are checked against their declarations (mapper_option_table.cc); each
// stage's struct checks its own.
void MapperOptions::Check() const {
  CheckOptionValues(MapperOptionTable(), *this);
  view_graph_calibration.Check();
  relative_pose.Check();
  view_graph.Check();
  rotation_averaging.Check();
  pair_direction.Check();
  direction_consistency.Check();
  translation_averaging.Check();
  translation_windows.Check();
  triangulation.Check();
  reregistration.Check();
  bundle_adjustment.Check();
  given_intrinsics_test.Check();
}

}  // namespace ramap
