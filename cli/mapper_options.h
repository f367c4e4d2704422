// The mapper's options on the command line, COLMAP-style (--Section.option), shared by every
// command that runs the mapper (mapper, compare, reconstruct). The options themselves are
// declared in the library (pipeline/mapper_option_table.h).
#pragma once

#include <CLI/CLI.hpp>

#include "ramap/pipeline/mapper_options.h"

namespace ramap::cli {

// Registers every mapper option (--RelativePose.*, --ViewGraph.*, --RotationAveraging.*,
// --TranslationAveraging.*, --PairDirection.*, --Triangulation.*, --Reregistration.*,
// --BundleAdjustment.*, --ViewGraphCalibration.*, --Mapper.*) bound to `options`.
void AddMapperOptions(CLI::App& app, MapperOptions* options);

}  // namespace ramap::cli
