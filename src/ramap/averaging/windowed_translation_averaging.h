// Translation averaging of a long sequence window by window: the keyframed structure of "Pushing
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

namespace ramap {

struct WindowedTranslationOptions {
  // Sequences of at least this many rotated images are solved in windows; shorter ones, and
  // unordered collections, in one system. 0: never in windows. The benchmark sets have at most
  // 160 frames, so their results do not change. Measured (scripts/bench_scale.sh, averaging alone,
  // ATE / path, one system -> windows of 30 sharing 20): KITTI 00 at 1000 frames 0.29% -> 0.58%
  // (translation averaging 1.7 -> 1.0 s), 2000 frames 0.88% -> 0.28%, 4541 frames 0.03% -> 0.09%
  // (12.3 -> 7.1 s); the KITTI 06 drive 0.20% -> 0.19% (2.4 -> 1.5 s). Those were the windows'
  // first measurements; with the later pair-direction cap, one BLAS thread per window and
  // irls_cost_tolerance below: 1000 frames 0.49%, 4541 frames 0.09% in 2.8 s (BENCHMARKS.md,
  // "Scale").
  int min_num_images = 1000;
  // Frames per window (the paper's keyframe interval is 30).
  int window_frames = 30;
  // Frames each window shares with the next; at least two, fewer than window_frames. The shared
  // frames carry the scale from one window to the next, and a window's first and last frames are
  // its least constrained, so the overlap is wide. Measured (ATE / path at 1000, 2000 and 4541
  // frames of KITTI 00 and on KITTI 06): 30 sharing 10 0.86 / 0.40 / 0.12 / 0.23%, 30 sharing 20
  // 0.58 / 0.28 / 0.09 / 0.19%, 60 sharing 20 0.62 / 0.44 / 0.08 / 0.14%.
  int overlap_frames = 20;
  // The windows' own TranslationAveragingOptions::irls_cost_tolerance (one system keeps its own):
  // a window's IRLS stops when a step lowers its objective by less than this share. Small systems
  // settle early and their remaining steps are what the alignment averages away. Measured
  // (scripts/bench_scale.sh): the 148 windows of 4541 frames take 2225 steps instead of 3799,
  // translation averaging 3.4 -> 2.9 s, ATE the same at 1000, 2000 and 4541 frames and on KITTI
  // 06 (0.49, 0.18, 0.09, 0.19%); 1e-3 also the same, at 1890 steps.
  double irls_cost_tolerance = 1e-4;
  WindowAlignmentOptions alignment;

  // Throws InputError naming the --TranslationAveraging.window_* option when out of range.
  void Check() const;
};

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
