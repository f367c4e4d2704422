// `ramap compare`: every mapper of CompareOptions on the same database, each as its own process
// timed as a whole, each largest model evaluated against the same reference (the ground truth, or
// without one the reference COLMAP's model). Writes report.md, report.json and the figures.
#pragma once

#include "ramap/compare/compare_options.h"
#include "ramap/compare/comparison.h"

namespace ramap {

// Checks the options and the output folder before any run (InputError naming the option), runs
// the mappers, evaluates them, draws the figures and writes the reports (the Markdown also to
// stdout). Throws InputError after writing the reports when a mapper failed: the report says which.
Comparison CompareMappers(const CompareOptions& options);

}  // namespace ramap
