// Stage 4 of the mapper on one component: the direction of every pair rotation averaging kept,
// from the averaged rotations (averaging/pair_directions.h), then translation averaging on them
// and on feature tracks (averaging/translation_averaging.h). With pose priors, the positions are
// aligned to their priors and, by default, solved again with the priors as rows.
#pragma once

#include "ramap/mapper/mapper_state.h"

namespace ramap {

// Starts building the tracks of every edge of `graph`: on a thread of its own with more than one
// mapper thread, otherwise when first asked for.
EarlyTracks StartComponentTracks(const PassInput& input, const RotationGraph& graph);

// The pair directions and tracks of the edges rotation averaging kept (the early tracks when they
// are built over exactly those), then the camera centres, in state.translations; none when
// translation averaging fails (the component's images get the reason).
ComponentState AverageComponentTranslations(const PassInput& input, ComponentState state);

// With pose priors (and PriorAlignmentOptions::align): fits the averaged centres to the priors;
// with the fit and use_in_translation_averaging, solves translation averaging again with the
// inlier priors as rows (in the model frame) and fits once more, so that the outliers and the
// residuals reported are those of the final positions.
ComponentState AlignComponentToPriors(const PassInput& input, ComponentState state);

// After the final model: the priors' errors and the outliers reported; the alignment's summary
// into the component's.
ComponentState ReportPriorErrors(const PassInput& input, ComponentState state);

}  // namespace ramap
