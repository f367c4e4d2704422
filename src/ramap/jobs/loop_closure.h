// Loop closure for image-list input matched sequentially: the loop candidates of a first solve
// (graph/loop_candidates.h: positions close) are matched and verified (enough inliers), so that a
// second solve has the loop edges in its view graph. When the first solve splits into several
// models (or leaves images out), pairs between them are screened by preemptive matching and the
// survivors matched too, so that the second solve can join them: positions say nothing across
// models.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "ramap/features/feature_matching.h"
#include "ramap/graph/loop_candidates.h"
#include "ramap/mapper/mapper.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct LoopClosureOptions {
  LoopCandidateOptions candidates;
  // Pairs between two models of the first solve (or a model and the unregistered images) at most,
  // evenly sampled from both; 0 turns the bridging off.
  int max_bridge_pairs = 1000;

  void Check() const;  // throws InputError("--LoopClosure...")
};

// Its options (--LoopClosure.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<LoopClosureOptions>& LoopClosureOptionTable();

struct LoopClosureSummary {
  int num_candidates = 0;
  int num_verified = 0;               // candidates that got a two-view geometry: the loop edges
  int num_bridge_pairs = 0;           // pairs between models, screened
  int num_bridge_pairs_matched = 0;   // kept by the screening and matched
  int num_bridge_pairs_verified = 0;  // with a two-view geometry
  std::vector<std::string> loops;     // "NAME1 NAME2: N inliers"
  double seconds = 0.0;
};

// Candidates in every model of `first` and bridge pairs between models, matched and verified into
// `database` (descriptors needed).
LoopClosureSummary MatchLoopCandidates(const MapperResult& first, const LoopClosureOptions& options,
                                       const FeatureMatchingOptions& matching,
                                       FeatureDatabase* database, std::ostream* progress = nullptr);

struct LoopClosedMapperResult {
  MapperResult result;            // the second solve's when a loop was verified, else the first's
  LoopClosureSummary closure;     // empty when loop closure was off
  bool database_changed = false;  // loop or bridge pairs were verified into the database
};

// The method's loop-closure step around the mapper (docs/architecture.md, stage 7): a first solve;
// with `close_loops`, its loop candidates and bridge pairs matched and verified into `database`
// and, when any was verified, a second solve with them. `progress` gets the mapper's lines and one
// loop-closure line.
LoopClosedMapperResult RunMapperWithLoopClosure(FeatureDatabase* database,
                                                const MapperOptions& options, bool close_loops,
                                                const LoopClosureOptions& closure_options,
                                                const FeatureMatchingOptions& matching,
                                                const std::string& source, std::ostream* progress,
                                                const PosePriors& priors);

// The options and the summary, as summary.json's "loop_closure".
nlohmann::json LoopClosureToJson(bool enable, const LoopClosureOptions& options,
                                 const LoopClosureSummary& closure);

}  // namespace ramap
