// The options of the steps before the mapper (reading images, features, matching, the database
// written) and of `ramap reconstruct` as a whole, declared once (util/option_table.h), like the
// mapper's (mapper/mapper_options.h).
#pragma once

#include "ramap/features/feature_extraction.h"
#include "ramap/features/feature_matching.h"
#include "ramap/features/image_reader.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/jobs/loop_closure.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct FeatureOptions {
  ImageReaderOptions reader;
  FeatureExtractionOptions extraction;
  FeatureMatchingOptions matching;
  // The generation of the database written (3.8: read by every COLMAP, 4.x upgrades it).
  DatabaseGeneration generation = DatabaseGeneration::kColmap38;
};

// Images into a model: features, matching, the mapper and, after sequential matching, loops.
struct ReconstructOptions {
  FeatureOptions features;
  MapperOptions mapper;
  bool close_loops = true;
  LoopClosureOptions loop_closure;
};

// --ImageReader.*, --FeatureExtraction.*, --Database.generation.
const OptionTable<FeatureOptions>& ExtractionOptionTable();
// --Matching.*.
const OptionTable<FeatureOptions>& MatchingOptionTable();
// Every option of `ramap reconstruct`: extraction, matching, the mapper's, --LoopClosure.*.
const OptionTable<ReconstructOptions>& ReconstructOptionTable();

// Checks every value against its declaration, then the cross-option rules; throws InputError.
void ResolveFeatureOptions(FeatureOptions* options);
void ResolveReconstructOptions(ReconstructOptions* options);

}  // namespace ramap
