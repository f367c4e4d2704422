// The mapper's options, each declared once (util/option_table.h): `ramap mapper`, `reconstruct`,
// `relative_poses`, `rotation_averager` and `bundle_adjuster` register them, summary.json lists
// them, Python takes them by these names, and docs/options.md is generated from them.
#pragma once

#include <string>
#include <vector>

#include "ramap/pipeline/mapper_options.h"
#include "ramap/util/option_table.h"

namespace ramap {

// Every mapper option, by section: RelativePose, ViewGraph, RotationAveraging,
// TranslationAveraging, PairDirection, Triangulation, Reregistration, BundleAdjustment,
// ViewGraphCalibration, Mapper.
const OptionTable<MapperOptions>& MapperOptionTable();

// The declarations of the given sections (and the single options named in `extra`), in table
// order: the subset a command that runs some of the stages registers.
OptionTable<MapperOptions> MapperOptionSections(const std::vector<std::string>& sections,
                                                const std::vector<std::string>& extra = {});

// Settings a caller builds before a run resolved once, in the library: BA's threads follow
// num_threads, and every value is checked against its declaration, then the cross-option rules
// (MapperOptions::Check). Throws InputError naming the option.
void ResolveMapperOptions(MapperOptions* options);

}  // namespace ramap
