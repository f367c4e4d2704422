// Stage 3 of the mapper on one component: rotation averaging of its view graph
// (estimators/rotations.h), keyframe windows first for sequences.
#pragma once

#include "ramap/mapper/mapper_state.h"

namespace ramap {

// The component's rotations and edge statuses; the images left without a rotation and the pruned
// edges in its report with their reasons, the rotation figures in its summary.
ComponentState AverageComponentRotations(const PassInput& input, ComponentState state);

}  // namespace ramap
