// One run of the mapper as a user asks for it: a COLMAP database in, the models (and
// summary.json) out. `ramap mapper` and Python's ramap.global_mapping are this one function, so
// that they give the same models for the same options.
#pragma once

#include <ostream>
#include <string>

#include "ramap/io/colmap_model.h"
#include "ramap/mapper/mapper.h"
#include "ramap/mapper/mapper_options.h"

namespace ramap {

struct MapperJob {
  std::string database_path;
  std::string image_path;   // optional: the points take their colours from these images
  std::string output_path;  // models 0, 1, ... and summary.json; empty: nothing is written
  ModelFormat output_format = ModelFormat::kBinary;
  MapperOptions options;
  std::string command = "ramap mapper";  // what warnings are prefixed with
};

// Reads the database and the pose priors the options name, runs the mapper, colours the
// points and writes everything into output_path at once (util/staged_output.h). One line per
// stage goes to `progress` and warnings to `warnings`, when given. Throws InputError naming the
// file or option at fault, NothingReconstructed when no component could be made.
MapperResult RunMapperJob(const MapperJob& job, std::ostream* progress, std::ostream* warnings);

}  // namespace ramap
