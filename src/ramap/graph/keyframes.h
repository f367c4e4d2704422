// Sequential keyframing of an ordered frame sequence and the local windows it induces, as in
// "Pushing the Envelope of Rotation Averaging for Visual SLAM" (Li, Yuan, Latecki, Ling): a
// keyframe every N frames; the frames between two consecutive keyframes (both included) form a
// densely connected local sub-graph; edges joining frames of no common window are loop edges.
#pragma once

#include <cstdint>
#include <vector>

#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct KeyframeOptions {
  // A keyframe every this many frames (the paper uses 30).
  int keyframe_interval = 30;
  // Throws InputError("--ViewGraph.keyframe_interval", ...) when out of range.
  void Check() const;
};

// Its options (--ViewGraph.*), each declared once with its range and help (util/option_table.h):
// the command line, Check(), summary.json and Python read them.
const OptionTable<KeyframeOptions>& KeyframeOptionTable();

struct KeyframeWindow {
  uint32_t first_keyframe = 0;   // node id
  uint32_t second_keyframe = 0;  // node id
  std::vector<uint32_t> frames;  // node ids in sequence order, both keyframes included
};

struct Keyframes {
  std::vector<uint32_t> keyframe_ids;   // in sequence order; the first and last frame are keyframes
  std::vector<KeyframeWindow> windows;  // windows[k] runs from keyframe k to keyframe k + 1
};

// Keyframes of `frames_in_order` (node ids in capture order). A sequence of one frame has one
// keyframe and no window, an empty one none. Throws InputError when options fail Check().
Keyframes SelectKeyframes(const std::vector<uint32_t>& frames_in_order,
                          const KeyframeOptions& options);

enum class EdgeKind { kLocal, kLoop };

// kLocal for an edge whose two frames lie in one window, kLoop otherwise (also for edges naming a
// frame absent from the sequence).
std::vector<EdgeKind> ClassifyEdges(const RotationGraph& graph, const Keyframes& keyframes);

}  // namespace ramap
