// Translation averaging of a long sequence window by window: the keyframe scheme of "Pushing
// the Envelope of Rotation Averaging for Visual SLAM" (Li, Yuan, Latecki, Ling) for positions.
//
// The sequence is cut into windows of consecutive frames (a keyframe interval long), each sharing
// its last frames with the next. Each window is solved alone by AverageTranslations
// (translation_averaging.h) on its pair directions and the parts of the tracks it sees, on the
// mapper's threads; AlignWindows (window_alignment.h) then places the windows in one frame from
// their shared frames and the pair directions between frames of no common window (the loops).
// The global problem has four unknowns per window instead of three per camera and a few rows per
// loop pair instead of every track, so its cost no longer grows with the tracks of the sequence.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "ramap/averaging/translation_averaging.h"
#include "ramap/averaging/window_alignment.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct WindowedTranslationOptions {
  // Sequences of at least this many rotated images are solved in windows; shorter ones, and
  // unordered collections, in one system. 0: never in windows. One system's cost grows with the
  // tracks of the whole sequence, a window's does not: windows save time on long drives, while
  // shorter sequences solve as quickly, and as accurately or better, in one system. The benchmark
  // sets have at most 160 frames, so their results do not change (BENCHMARKS.md, "Scale").
  int min_num_images = 1000;
  // Frames per window (the paper's keyframe interval is 30).
  int window_frames = 30;
  // Frames each window shares with the next; at least two, fewer than window_frames. The shared
  // frames carry the scale from one window to the next, and a window's first and last frames are
  // its least constrained, so the overlap is wide: a narrower one drifted more on every drive,
  // and longer windows gained on some drives and lost on others (BENCHMARKS.md, "Scale").
  int overlap_frames = 20;
  // The windows' own TranslationAveragingOptions::irls_cost_tolerance (one system keeps its own):
  // a window's IRLS stops when a step lowers its objective by less than this share. Small systems
  // settle early and their remaining steps are what the alignment averages away: stopping them
  // saves steps and time at the same accuracy, and a looser tolerance saved few more steps
  // (BENCHMARKS.md, "Scale").
  double irls_cost_tolerance = 1e-4;
  WindowAlignmentOptions alignment;

  // Throws InputError naming the --TranslationAveraging.window_* option when out of range.
  void Check() const;
};

// Its options (--TranslationAveraging.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<WindowedTranslationOptions>& WindowedTranslationOptionTable();

// Positions of the cameras of `rotations` as AverageTranslations gives them (the same gauge:
// the first positioned image of `order` at the origin, mean projected pair baseline 1), solved in
// windows along `order` (image ids in capture order; images absent from `rotations` are skipped).
// A window whose own solve fails leaves its images to the other windows. Throws StageFailure when
// the windows cannot be joined (window_alignment.h), so that the caller can solve in one system.
TranslationAveragingResult AverageTranslationsInWindows(
    const std::vector<uint32_t>& order, const std::map<uint32_t, Eigen::Quaterniond>& rotations,
    const std::vector<PairDirection>& pair_directions, const std::vector<Track>& tracks,
    const KeypointBearings& bearings, const TranslationAveragingOptions& options,
    const WindowedTranslationOptions& windowed, int num_threads);

}  // namespace ramap
