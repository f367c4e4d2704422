// Capture order of images from their names, for sequential input: "frame_000123.png" sorts by the
// number at the end of its stem (numerically, so "img_9" comes before "img_10").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ramap/scene/features.h"

namespace ramap {

enum class InputOrder {
  kAuto,        // sequential when image names end in increasing frame numbers
  kSequential,  // frames in name order, keyframe windows
  kUnordered,   // one global view graph
};

// Positions of `names` in capture order: by the name's prefix, then by its trailing frame number,
// then by the whole name (names without a number sort by name within their prefix).
std::vector<size_t> CaptureOrder(const std::vector<std::string>& names);

// True when every name ends in a frame number and all share one prefix: a video or a drive.
bool LooksSequential(const std::vector<std::string>& names);

// Whether images of these names are treated as a sequence under `order` (kAuto: LooksSequential).
bool IsSequentialInput(InputOrder order, const std::vector<std::string>& names);

// The image ids of `database` in the CaptureOrder of their names.
std::vector<uint32_t> ImageIdsInCaptureOrder(const FeatureDatabase& database);

}  // namespace ramap
