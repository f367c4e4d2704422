// The comparison of mappers on one database (`ramap compare`): COLMAP's incremental BA mapper, the
// peers (a newer COLMAP's incremental mapper and GLOMAP) when given, and ramap's averaging mapper
// with and without bundle adjustment, each timed as a whole process and evaluated against the same
// reference. Plain data and its report (JSON for programs, Markdown for people); running the
// mappers is compare_mappers.h's.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ramap/eval/pose_metrics.h"

namespace ramap {

// Row names of the runs, as the reports and scripts/benchmark_table.py know them.
namespace mapper_row {
inline constexpr const char* kColmap = "COLMAP";  // the reference (speed ratios over it)
inline constexpr const char* kGlomap = "GLOMAP";  // the peer's global mapper
inline constexpr const char* kRamap = "ramap";
inline constexpr const char* kRamapBa = "ramap+BA";
}  // namespace mapper_row

struct MapperRun {
  std::string name;        // "COLMAP", "COLMAP 4.1.1", "GLOMAP", "ramap", "ramap+BA"
  std::string command;     // the exact command line that was run
  std::string model_path;  // the largest model it wrote ("" when it wrote none)
  bool succeeded = false;  // exit code 0 and a model
  double seconds = 0.0;    // wall time of the whole process
  int num_models = 0;
  int num_registered = 0;  // images of the largest model
  // The mean focal length (px) of each camera of the largest model, by camera id: what the mapper
  // calibrated, when it refined the intrinsics.
  std::map<uint32_t, double> focal_lengths_px;
  // Per-stage seconds as the mapper reported them (ramap's summary.json); empty for COLMAP.
  std::vector<std::pair<std::string, double>> stage_seconds;
  // Against the reference; empty when there is none for this run (the reference run itself).
  std::optional<PoseEvaluation> evaluation;
};

struct Comparison {
  std::string database_path;
  std::string reference;  // "ground truth PATH (FORMAT)" or "the COLMAP model"
  int num_images = 0;
  std::vector<MapperRun> runs;       // runs[0] is COLMAP's: speed ratios are relative to it
  std::string peer_version;          // the peer COLMAP's version ("" without peers)
  std::vector<std::string> figures;  // file names, relative to the report
};

// Every number of the comparison, including per-run evaluations (without per-image rows) and the
// speed ratios (COLMAP's seconds over each run's; with a GLOMAP run, also GLOMAP's over each's).
nlohmann::json ComparisonToJson(const Comparison& comparison);

// The same as a short Markdown report: one table, the speed ratios (with a GLOMAP run, a line of
// each ramap run's ratio against it at their AUC@3), the commands and the figures.
std::string ComparisonToMarkdown(const Comparison& comparison);

}  // namespace ramap
