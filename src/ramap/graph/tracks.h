// Feature tracks: the connected sets of (image, keypoint) linked by verified matches.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

using Track = std::vector<TrackElement>;

struct TrackBuildOptions {
  // A track must see at least this many images (two give a triangulable point).
  int min_track_length = 2;
};

struct TrackBuildSummary {
  int num_tracks = 0;
  // Tracks that saw one image at two different keypoints: inconsistent matches, dropped whole.
  int num_conflicting_tracks = 0;
  int num_short_tracks = 0;
};

// Tracks from the inlier matches of `geometries`, restricted to the pairs in `use_pairs` when it is
// not empty. Elements of a track are sorted by image id; tracks are sorted by their first element,
// so the result is deterministic.
std::vector<Track> BuildTracks(const std::map<uint64_t, TwoViewGeometry>& geometries,
                               const std::set<uint64_t>& use_pairs = {},
                               const TrackBuildOptions& options = TrackBuildOptions(),
                               TrackBuildSummary* summary = nullptr);

}  // namespace ramap
