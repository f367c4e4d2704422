// Pair directions checked against the short cycles they close, before translation averaging.
//
// For three images a, b, c whose three pairs all have directions, c_b - c_a = |c_c - c_a| d_ac +
// |c_b - c_c| d_cb with both lengths positive, so d_ab must lie in the cone of d_ac and d_cb; a
// pair with no such triangle (one that skips more frames than the others match) is tested the
// same way on quadrilaterals a -> c -> d -> b. A cycle's residual is the angle from d_ab to its
// cone, counted only when its legs point within 90 deg of each other (legs back past a and
// forward past b span half a plane and hold any direction and its opposite). A direction's
// consistency is the lower quartile of its cycles' residuals: a wrong direction spoils all of
// them, a right one only those it shares with a wrong one. A pair whose matches obey a wrong pose
// (repeated facades aliased) gives a direction that its cycles do not support, and it must not
// serve as a row nor as the reference of the tracks it sees: the widest pair of a track, often
// such a pair, sets the depth of each of its predictions (translation_averaging.h), and its wrong
// matches would put wrong observations on the tracks.
// This is the loop-consistency idea of Zach, Klopschitz and Pollefeys ("Disambiguating visual
// relations using loop constraints", CVPR 2010) on the shortest loops of directions, with a
// threshold from the residuals' own distribution rather than a fixed angle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ramap/averaging/translation_averaging.h"
#include "ramap/util/option_table.h"

namespace ramap {

enum class DirectionCheckMode {
  kOff,       // every direction is used
  kFixed,     // rejected above max_residual_deg
  kAdaptive,  // rejected above threshold_multiplier times the median consistency, clamped
};

struct DirectionConsistencyOptions {
  DirectionCheckMode mode = DirectionCheckMode::kAdaptive;
  // kAdaptive: the threshold is threshold_multiplier times the median consistency of the tested
  // pairs (what noise gives), at least min_threshold_deg and at most max_residual_deg.
  double threshold_multiplier = 8.0;
  double min_threshold_deg = 1.0;
  // kFixed: the threshold; kAdaptive: its ceiling.
  double max_residual_deg = 10.0;
  // A pair closing fewer cycles than this is not tested (kept): one cycle cannot tell which of its
  // directions is wrong.
  int min_num_cycles = 3;
  // Cycles per pair at most (the first ones in image order); bounds the cost where loops give a
  // pair many.
  int max_num_cycles = 40;
  // Rounds at most: each rejects the directions above the threshold, worst first, but one that
  // shares a cycle with a direction rejected in the same round waits for the next, which forms
  // the cycles again without it (a wrong direction spoils the cycles of its neighbours).
  int num_rounds = 10;

  // Throws InputError naming the --TranslationAveraging.direction_* option out of range.
  void Check() const;
};

// Its options (--TranslationAveraging.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<DirectionConsistencyOptions>& DirectionConsistencyOptionTable();

struct RejectedDirection {
  uint32_t image_id1 = 0;
  uint32_t image_id2 = 0;
  double consistency_deg = 0.0;  // the lower quartile of its cycles' residuals
  double threshold_deg = 0.0;
  int num_cycles = 0;
  int round = 0;  // 1-based
};

struct DirectionConsistencyResult {
  std::vector<PairDirection> kept;  // in their given order
  std::vector<RejectedDirection> rejected;
  int num_tested = 0;                   // pairs with at least min_num_cycles cycles (first round)
  double median_consistency_deg = 0.0;  // of the tested pairs (first round)
  double threshold_deg = 0.0;           // of the last round that tested any pair
};

// The angle (radians) from unit `direction` to the cone {s u + t v : s, t >= 0} of unit u and v.
double AngleToCone(const Eigen::Vector3d& direction, const Eigen::Vector3d& u,
                   const Eigen::Vector3d& v);

// Splits `directions` (world-frame unit directions of c2 - c1) into the kept and the rejected.
DirectionConsistencyResult CheckDirectionCycles(const std::vector<PairDirection>& directions,
                                                const DirectionConsistencyOptions& options);

}  // namespace ramap
