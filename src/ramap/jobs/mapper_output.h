// Writing what the mapper produced: one COLMAP model per component (DIR/0, DIR/1, ...; largest
// first, as COLMAP numbers them), each with its TUM trajectory, DIR/summary.json and
// DIR/report.html (report/html_report.h).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "ramap/io/colmap_model.h"
#include "ramap/mapper/mapper.h"

namespace ramap {

// The summary as JSON: counts, per-stage seconds, per-component certificates, dropped images and
// edges with their reasons.
nlohmann::json MapperSummaryToJson(const MapperSummary& summary);

// Writes everything into `output_path` (created when missing). Everything is written under a
// temporary folder first and moved into place only when complete, so a failure leaves no partial
// model; model folders of an earlier run numbered beyond this run's components are removed.
// `run_info` (options, input path, version) is stored in summary.json under "run". A report.html
// that cannot be made is left out with a warning to `warnings`, when given. With more than one of
// `num_threads`, the report is built while the models are written.
void WriteMapperOutput(const MapperResult& result, const std::string& output_path,
                       ModelFormat format, const nlohmann::json& run_info,
                       std::ostream* warnings = nullptr, int num_threads = 1);

}  // namespace ramap
