// What `ramap mapper` and `ramap reconstruct` print after a run: the summary table and the
// prior alignment of each model.
#pragma once

#include <ostream>
#include <string>

#include "ramap/mapper/mapper_summary.h"

namespace ramap::cli {

// One line per model saying whether (and how well) it was aligned to its priors, then the rejected
// priors (ten at most); nothing when the run had no priors.
void PrintPriorAlignment(const MapperSummary& summary, std::ostream& out);

// The run in a table: models, points, residuals, certificates, prior alignment, the focal lengths
// the database did not know or BA changed, and the first ten images not registered.
void PrintMapperSummary(const MapperSummary& summary, const std::string& output_path,
                        std::ostream& out);

}  // namespace ramap::cli
