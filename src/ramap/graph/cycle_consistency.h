// A lower bound on the residuals of ANY rotation assignment, from the graph's own cycles.
// If the relative rotations around a triangle a -> b -> c -> a compose to a rotation of angle
// theta, every assignment of absolute rotations leaves a residual of at least theta / 3 on one of
// the three edges: the composed rotation is the product of the three edge errors (conjugated, which
// keeps their angles), and on SO(3) the angle of a product is at most the sum of the angles.
// Rotation averaging uses it to skip the chordal refinement of its optimality certificate when no
// stationary point could pass the strong-duality bound (Eriksson et al., CVPR 2018).
#pragma once

#include <vector>

#include "ramap/graph/rotation_graph_algorithms.h"

namespace ramap {

struct TriangleCycleBound {
  double residual_lower_bound_deg = 0.0;  // max over the triangles seen of cycle angle / 3
  size_t triangles_checked = 0;
};

// Enumerates the triangles of the edges with keep[e] between nodes with active[k] (node positions)
// and returns the largest cycle angle / 3 seen. Stops at the first triangle above
// `stop_above_deg` (pass infinity to check all). Parallel edges: the first kept one of each pair is
// used, which still gives a valid bound.
TriangleCycleBound TriangleCycleResidualBound(const RotationGraph& graph,
                                              const std::vector<bool>& keep,
                                              const std::vector<bool>& active,
                                              double stop_above_deg);

}  // namespace ramap
