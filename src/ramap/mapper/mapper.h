// The mapper: a COLMAP database in, one COLMAP model per connected component out, by motion
// averaging instead of incremental bundle adjustment. The stages follow docs/architecture.md and
// the method section of "Pushing the Envelope of Rotation Averaging for Visual SLAM" (Li, Yuan,
// Latecki, Ling):
//   1. relative rotations of every verified pair (grid-selected six points, Kneip's solvers);
//   2. the view graph: keyframe windows for sequences, every accepted pair for collections;
//   3. robust rotation averaging with pruning and a certificate;
//   4. pair directions with the averaged rotations, then translation averaging on feature tracks;
//   5. triangulation with the poses fixed;
//   6. optionally, bundle adjustment.
// With pose priors (GPS), each component is aligned to its priors after translation averaging
// (estimators/prior_alignment.h), translation averaging is solved again with the priors as weak
// rows, and the model is triangulated, refined and written in the priors' metric frame.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_summary.h"
#include "ramap/scene/features.h"
#include "ramap/scene/geodetic_point.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

struct MapperResult {
  // Largest component first; each one aligned to its priors in their frame (summary.components[k]
  // says which).
  std::vector<Reconstruction> reconstructions;
  MapperSummary summary;
  // The geodetic origin of that frame (east-north-up), when the priors had one.
  std::optional<GeodeticPoint> geodetic_origin;
};

// Runs every stage on `database`. Throws InputError (naming `source`, e.g. the database path) when
// nothing can be reconstructed: no verified pairs, no relative pose, no component of
// min_component_size images. `progress` receives one line per stage. `priors` (keyed by image id)
// align the components that have enough of them; the others are written as without priors,
// with the reason in their summary.
MapperResult RunMapper(const FeatureDatabase& database, const MapperOptions& options,
                       const std::string& source, std::ostream* progress = nullptr,
                       const PosePriors& priors = PosePriors());

}  // namespace ramap
