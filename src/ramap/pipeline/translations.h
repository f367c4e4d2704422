// Stage 4 of the mapper on one component: the direction of every pair rotation averaging kept,
// from the averaged rotations (averaging/pair_directions.h), then translation averaging on them
// and on feature tracks (averaging/translation_averaging.h). With pose priors, the positions
// are aligned to their priors and, by default, solved again with the priors as rows.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <future>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "ramap/averaging/pair_directions.h"
#include "ramap/averaging/rotation_averaging.h"
#include "ramap/averaging/translation_averaging.h"
#include "ramap/graph/tracks.h"
#include "ramap/pipeline/mapper_context.h"
#include "ramap/pipeline/prior_alignment.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/relative_rotations.h"

namespace ramap {

struct ComponentTranslations {
  std::vector<PairDirection> directions;
  std::vector<Track> tracks;  // feature tracks over the kept pairs (triangulated later)
  TranslationAveragingResult positions;
  // Kept pure-rotation edges, both ways: they place the images nothing else positions.
  std::multimap<uint32_t, uint32_t> pure_rotation_neighbours;
  bool tracks_built_early = false;  // the EarlyTracks fitted what rotation averaging kept
};

// The tracks of a whole component, built before its rotations are averaged: rotation averaging
// runs mostly on one thread (a second one barely speeds it), and leaves the other core to them.
// They are the tracks translation averaging needs when rotation averaging keeps every edge, the
// common case, which makes a long drive's translation stage quicker (BENCHMARKS.md, "Scale");
// otherwise translation averaging builds them again over the edges it kept.
struct EarlyTracks {
  std::set<uint64_t> pair_ids;  // the edges they are built over
  std::future<std::vector<Track>> built;
};

// Starts building the tracks of every edge of `graph`: on a thread of its own with more than one
// mapper thread, otherwise when first asked for.
EarlyTracks StartComponentTracks(const MapperContext& context, const ViewGraph& graph);

// The pair directions and tracks of the edges with edge_status kKept (the `early` ones when they
// are built over exactly those), then the camera centres; none when translation averaging fails
// (the component's images get the reason).
std::optional<ComponentTranslations> AverageComponentTranslations(
    const MapperContext& context, const ViewGraph& graph,
    const std::vector<EdgeStatus>& edge_status,
    const std::map<uint32_t, Eigen::Quaterniond>& world_rotations, EarlyTracks* early,
    MapperComponentSummary* component);

// Fits the averaged centres to context.priors; with the fit and use_in_translation_averaging,
// solves translation averaging again with the inlier priors as rows (in the model frame) and fits
// once more, so that the outliers and the residuals reported are those of the final positions
// (`translations->positions` then holds them). Records the progress line.
PriorAlignment AlignComponentToPriors(const MapperContext& context,
                                      const std::map<uint32_t, Eigen::Quaterniond>& rotations,
                                      ComponentTranslations* translations);

// After the final model: the priors' errors, and the outliers reported in the summary.
void ReportPriorErrors(const MapperContext& context, const Reconstruction& reconstruction,
                       PriorAlignment* prior_alignment);

}  // namespace ramap
