// What `ramap mapper` and `ramap reconstruct` print after a run: the summary table, the
// georegistration of each model, and the point colours read.
#pragma once

#include <ostream>
#include <string>

#include "ramap/io/point_colors.h"
#include "ramap/pipeline/mapper_summary.h"

namespace ramap::cli {

// One line per model saying whether (and how well) it was georegistered, then the rejected priors
// (ten at most); nothing when the run had no priors.
void PrintGeoregistration(const MapperSummary& summary, std::ostream& out);

// The run in a table: models, points, residuals, certificates, georegistration, the focal lengths
// the database did not know or BA changed, and the first ten images not registered.
void PrintMapperSummary(const MapperSummary& summary, const std::string& output_path,
                        std::ostream& out);

// The colours' progress line (when `log`), and a warning per image that could not be read.
void PrintPointColors(const PointColorSummary& colors, const std::string& image_path,
                      double seconds, std::ostream* log, std::ostream& warnings);

}  // namespace ramap::cli
