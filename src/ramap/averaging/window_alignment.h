// One frame for the camera centres of overlapping windows of a sequence, each solved alone.
//
// Once rotations are fixed, translation averaging determines a window's centres up to a scale and
// a translation; the window's placement c = s_w c_local + t_w moves them into the common frame
// (window 0 is held at s = 1, t = 0). Two kinds of 3-row residual tie the windows:
// - an image two windows share: s_a c_a + t_a - s_b c_b - t_b, over sqrt(s_a s_b) (in the windows'
//   own units). The overlaps carry the scale along the sequence, which directions alone leave
//   free on a straight stretch;
// - a pair direction d between images of no common window (loop closures, and neighbours across a
//   window boundary): (c_j - c_i) / |c_j - c_i| - d.
// Neither residual falls when every window shrinks, so the windows cannot collapse onto a point (a
// linear direction constraint, (I - d d^T)(c_j - c_i), would reward exactly that). The placements
// start from the least-squares chain of overlaps (linear) and are refined with the directions by
// Ceres under Huber losses, a similarity view graph with the rotations fixed.
// This is the back end of "Pushing the Envelope of Rotation Averaging for Visual SLAM"
// (Li, Yuan, Latecki, Ling) applied to positions: dense local windows solved alone, joined by
// their shared frames and the loop edges.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "ramap/averaging/translation_averaging.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct WindowAlignmentOptions {
  // Residuals of a shared image below this many times the median of the least-squares chain's
  // are weighed as squares, beyond as their norm (a Huber loss), so that one window solved
  // wrongly pulls on its neighbours with a bounded force.
  double huber_overlap_residuals = 3.0;
  // A cross direction's noise (radians): angles below it are weighed as squares, beyond as their
  // size (Huber), so that an aliased pair (tens of degrees off) pulls with a bounded force. On the
  // synthetic drives of scripts/bench_scale.sh a larger sigma let the longest drive drift more and
  // changed little on the shorter one.
  double direction_sigma_rad = 0.01;
  // Ceres iterations with the cross directions; 0: the least-squares chain of overlaps alone.
  // The cap is well above what the long synthetic drives need to converge; stopping them before
  // they converge left them less accurate.
  int max_num_iterations = 200;
  // Cross directions used per pair of windows at most (evenly spread over theirs); 0: all. A
  // revisit joins two windows by up to hundreds of pairs, which say much the same about their
  // eight unknowns: the synthetic drives of scripts/bench_scale.sh are as accurate with 20 as with
  // all, and no slower. It bounds the alignment's cost where loops are many.
  int max_directions_per_window_pair = 20;
  int num_threads = 1;  // Ceres's
};

// Its options (--TranslationAveraging.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<WindowAlignmentOptions>& WindowAlignmentOptionTable();

// c = scale * c_local + translation.
struct WindowPlacement {
  double scale = 1.0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

// Whether two windows (image id -> centre in the window's frame) share two images at distinct
// positions, which ties their relative scale as well as their offset.
bool WindowsTied(const std::map<uint32_t, Eigen::Vector3d>& a,
                 const std::map<uint32_t, Eigen::Vector3d>& b);

// Placements of `windows` (each: image id -> centre in the window's own frame), window 0 the
// identity. `cross_directions` are pair directions between images that share no window; those
// naming an image of no window are ignored. Throws StageFailure (util/error.h) when a window is
// not tied to window 0 by a chain of windows sharing two images at distinct positions, when the
// chain gives a window a scale that is not positive, or when Ceres fails.
std::vector<WindowPlacement> AlignWindows(
    const std::vector<std::map<uint32_t, Eigen::Vector3d>>& windows,
    const std::vector<PairDirection>& cross_directions,
    const WindowAlignmentOptions& options = WindowAlignmentOptions());

}  // namespace ramap
