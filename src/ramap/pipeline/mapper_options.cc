#include "ramap/pipeline/mapper_options.h"

namespace ramap {

// The Mapper.* ranges are the declarations' (mapper_option_table.cc, checked first by
// ResolveMapperOptions); each stage's struct checks its own.
void MapperOptions::Check() const {
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
