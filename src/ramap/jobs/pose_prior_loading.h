// The mapper's pose priors read from where PosePriorSource says (a prior file or the database's
// prior positions, where COLMAP stores EXIF GPS) into the images' local frame.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "ramap/estimators/prior_alignment.h"
#include "ramap/jobs/pose_priors.h"
#include "ramap/mapper/pose_prior_source.h"
#include "ramap/scene/features.h"

namespace ramap {

// The priors `source` names, in the local frame of `database`'s images: the file's when a path is
// given, else the database's (unless from_database is off). Skipped records are written to `log`
// as warnings prefixed by `command` (ten at most, then a count); nothing when `log` is null.
LocalizedPriors LoadPosePriors(const PosePriorSource& source, const FeatureDatabase& database,
                               const std::string& command, std::ostream* log);

// The source and the prior alignment settings as summary.json's "pose_priors" block.
nlohmann::json PosePriorOptionsToJson(const PosePriorSource& source,
                                      const PriorAlignmentOptions& prior_alignment);

}  // namespace ramap
