// Folds of a rotation averaging solution. A landmark whose back looks like its front (or a
// facade that repeats) gives pairs that verify, agree with each other in every small cycle, and
// are wrong. On a ring of views the solution that folds the far side onto the near side then
// leaves out only the few pairs where the fold cuts the ring, while the true one leaves out every
// wrong pair: unweighted L1 averaging prefers the fold, and nothing along the way between the two
// costs more. The pairs the fold cuts are strong (neighbours share most of their points) and the
// wrong ones weaker, so the inlier-weighted solution keeps the truth. Where the two solutions
// disagree grossly, the one that leaves out fewer inliers is the consistent part of the graph
// (a weighted consensus; the problem: Zach et al., "Disambiguating visual relations using loop
// constraints", CVPR 2010).
#pragma once

#include "ramap/averaging/rotation_averaging.h"

namespace ramap {

struct RotationSolutionComparison {
  int num_estimated_first = 0;
  int num_estimated_second = 0;
  // The largest angle between the two solutions' rotations of a node both estimated, once the
  // second is turned onto the first at the node with most edges (their gauges differ).
  double largest_difference_deg = 0.0;
  // The summed weight (inlier count) of the edges each solution left out (pruned, or cut off
  // from its largest component).
  double left_out_weight_first = 0.0;
  double left_out_weight_second = 0.0;
};

RotationSolutionComparison CompareRotationSolutions(const RotationGraph& graph,
                                                    const RotationAveragingResult& first,
                                                    const RotationAveragingResult& second);

// Whether the second solution should replace the first: they differ by more than
// `min_difference_deg` at some node, the second estimates as many nodes, and the edges it leaves
// out carry less weight.
bool SecondSolutionUnfolds(const RotationSolutionComparison& comparison, double min_difference_deg);

}  // namespace ramap
