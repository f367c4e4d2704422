#include "mapper_options.h"

#include "options.h"
#include "ramap/pipeline/mapper_option_table.h"

namespace ramap::cli {

void AddMapperOptions(CLI::App& app, MapperOptions* options) {
  AddOptionTable(app, MapperOptionTable(), options);
}

void AddLoopClosureOptions(CLI::App& app, bool* close_loops, LoopClosureOptions* options) {
  LoopCandidateOptions& loops = options->candidates;
  app.add_option("--LoopClosure.enable", *close_loops,
                 "1: after sequential matching, match the pairs a first solve puts close, solve "
                 "again")
      ->capture_default_str();
  app.add_option("--LoopClosure.max_distance_baselines", loops.max_distance_baselines,
                 "candidate centres within this many median frame-to-frame baselines")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--LoopClosure.max_view_angle_deg", loops.max_view_angle_deg)
      ->capture_default_str()
      ->check(NumberCheck(0, true, 180, false));
  app.add_option("--LoopClosure.min_frame_gap", loops.min_frame_gap,
                 "candidates are at least this many frames apart")
      ->capture_default_str()
      ->check(AtLeast(2));
  app.add_option("--LoopClosure.max_candidates_per_image", loops.max_candidates_per_image)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--LoopClosure.max_bridge_pairs", options->max_bridge_pairs,
                 "when the first solve splits, pairs between two models screened to join them "
                 "(0: off)")
      ->capture_default_str()
      ->check(AtLeast(0));
}

}  // namespace ramap::cli
