// Stage 6 of the mapper on one component: bundle adjustment of the averaged model
// (refine/bundle_adjustment.h), then every track triangulated again. The full adjustment
// (MapperOptions::refine, the default), or only that of a subset of the tracks
// (MapperOptions::subset_adjustment).
#pragma once

#include <vector>

#include "ramap/graph/tracks.h"
#include "ramap/pipeline/mapper_context.h"
#include "ramap/pipeline/prior_alignment.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// Bundle adjustment on the best-connected points of `reconstruction` (up to
// BundleAdjustmentOptions::max_num_points, or the subset's when MapperOptions::refine is off),
// with the inlier priors of a component aligned to its priors when use_in_bundle_adjustment; then
// `tracks` triangulated again with the refined poses into `reconstruction`, through the refined
// intrinsics when BA refined them (they change every bearing of the component's images).
void RefineComponent(const MapperContext& context, const std::vector<Track>& tracks,
                     PriorAlignment* prior_alignment, MapperComponentSummary* component,
                     Reconstruction* reconstruction);

}  // namespace ramap
