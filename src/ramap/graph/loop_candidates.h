// Loop candidates of a sequence: image pairs that a first solve puts close together, in position
// and viewing direction, but far apart in capture order, so sequential matching never compared
// them. This is the first step of a two-step loop test ("positions close"); the second
// ("enough verified inliers") is the matcher's verification of each candidate, after which the
// mapper solves again with the loop edges in the view graph.
#pragma once

#include <cstdint>
#include <set>
#include <vector>

#include "ramap/scene/reconstruction.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct LoopCandidateOptions {
  // Centres closer than this many median consecutive-frame baselines (the unit a first solve's
  // scale can be measured in)...
  double max_distance_baselines = 5.0;
  // ...optical axes within this angle (a revisit seen the other way round shares nothing)...
  double max_view_angle_deg = 30.0;
  // ...and at least this many frames apart in capture order (sequential matching's overlap is 10).
  int min_frame_gap = 20;
  // Candidates per image at most, the closest first: a car standing at a crossing would otherwise
  // make dozens.
  int max_candidates_per_image = 3;

  void Check() const;  // throws InputError("--LoopClosure.<option>", ...)
};

// Its options (--LoopClosure.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<LoopCandidateOptions>& LoopCandidateOptionTable();

struct LoopCandidate {
  uint32_t image_id1 = 0;  // image_id1 < image_id2
  uint32_t image_id2 = 0;
  double distance_baselines = 0.0;
  double view_angle_deg = 0.0;
};

// Candidates among the registered images of `reconstruction`; `capture_order` lists image ids in
// capture order; pairs in `matched_pair_ids` (COLMAP pair ids) are already matched and skipped.
// Closest first.
std::vector<LoopCandidate> FindLoopCandidates(const Reconstruction& reconstruction,
                                              const std::vector<uint32_t>& capture_order,
                                              const std::set<uint64_t>& matched_pair_ids,
                                              const LoopCandidateOptions& options);

}  // namespace ramap
