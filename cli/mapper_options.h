// The mapper's options on the command line, COLMAP-style (--Section.option), shared by every
// command that runs the mapper (mapper, compare, reconstruct).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "ramap/pipeline/loop_closure.h"
#include "ramap/pipeline/mapper.h"

namespace ramap::cli {

// Option strings that need converting after parsing (enums).
struct MapperOptionText {
  std::string sequential = "auto";
  std::string sampler = "grid";
  std::string loss = "geman_mcclure";
  std::string pruning = "adaptive";
  std::string translation_solver = "irls";
  std::string edge_weights = "auto";
  std::string direction_check = "adaptive";
};

// Stage 1: --RelativePose.* and --Mapper.num_threads.
void AddRelativePoseOptions(CLI::App& app, MapperOptions* options, MapperOptionText* text);
// Stages 2 and 3: --PoseGraph.* and --RotationAveraging.*.
void AddRotationAveragingOptions(CLI::App& app, MapperOptions* options, MapperOptionText* text);

// Adds --RelativePose.*, --PoseGraph.*, --RotationAveraging.*, --TranslationAveraging.*,
// --Triangulation.*, --BundleAdjustment.* and --Mapper.* options bound to `options` (defaults shown
// from the structs).
void AddMapperOptions(CLI::App& app, MapperOptions* options, MapperOptionText* text);
// The --BundleAdjustment.* options alone (the mapper's and `bundle_adjuster`'s).
void AddBundleAdjusterOptions(CLI::App& app, BundleAdjustmentOptions* options);

// Converts the enum options; throws InputError naming the option on a bad value.
void FinishMapperOptions(const MapperOptionText& text, MapperOptions* options);

// The options as JSON, for summary.json and reports.
nlohmann::json MapperOptionsToJson(const MapperOptions& options);

// --LoopClosure.*: whether `ramap reconstruct` closes loops after sequential matching, and how it
// finds the candidates (pipeline/loop_closure.h).
void AddLoopClosureOptions(CLI::App& app, bool* close_loops, LoopClosureOptions* options);

}  // namespace ramap::cli
