// One mapper run of a comparison: its command as a process of its own, timed as a whole, and the
// largest model it wrote.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "ramap/compare/comparison.h"
#include "ramap/compare/mapper_plans.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

// Throws InputError naming --output_path unless `plan`'s folder under `output_path` is absent or
// holds only an earlier run's output, and its log and database copy paths are free to be written
// (not folders, not the compared database). Checked for every plan before the first run starts.
void CheckRunFolder(const std::string& output_path, const MapperPlan& plan,
                    const std::string& database_path);

// Runs `plan` in its folder (replaced), its output in FOLDER.log, timed as a process (a peer's
// database copy is made before the clock starts and removed after). Its largest model, read
// once, goes to `model` (left empty when the run failed).
MapperRun RunMapperPlan(const MapperPlan& plan, const CompareOptions& options, size_t num_images,
                        Reconstruction* model);

}  // namespace ramap
