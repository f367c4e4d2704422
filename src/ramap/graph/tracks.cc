#include "ramap/graph/tracks.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "ramap/util/disjoint_sets.h"

namespace ramap {
namespace {

// Dense numbering of the (image, keypoint) observations the matches mention: each image's keypoint
// indices up to the largest matched one, images in increasing id.
struct ObservationIndex {
  std::map<uint32_t, uint32_t> offset;  // image id -> first dense index
  std::map<uint32_t, uint32_t> size;    // image id -> 1 + largest matched keypoint index
  uint32_t total = 0;
};

template <typename UsePair>
ObservationIndex IndexObservations(const std::map<uint64_t, TwoViewGeometry>& geometries,
                                   const UsePair& use) {
  ObservationIndex index;
  for (const auto& [pair_id, geometry] : geometries) {
    if (!use(pair_id)) continue;
    uint32_t& size1 = index.size[geometry.image_id1];
    uint32_t& size2 = index.size[geometry.image_id2];
    for (const FeatureMatch& match : geometry.inlier_matches) {
      size1 = std::max(size1, match.point2D_idx1 + 1);
      size2 = std::max(size2, match.point2D_idx2 + 1);
    }
  }
  uint64_t total = 0;
  for (const auto& [image_id, size] : index.size) {
    index.offset[image_id] = static_cast<uint32_t>(total);
    total += size;
  }
  if (total >= std::numeric_limits<uint32_t>::max()) {
    throw std::length_error("BuildTracks: more than 4 billion matched keypoints");
  }
  index.total = static_cast<uint32_t>(total);
  return index;
}

}  // namespace

std::vector<Track> BuildTracks(const std::map<uint64_t, TwoViewGeometry>& geometries,
                               const std::set<uint64_t>& use_pairs,
                               const TrackBuildOptions& options, TrackBuildSummary* summary) {
  const auto use = [&](uint64_t pair_id) { return use_pairs.empty() || use_pairs.count(pair_id); };
  const ObservationIndex index = IndexObservations(geometries, use);
  DisjointSets sets(index.total);
  std::vector<bool> matched(index.total, false);
  for (const auto& [pair_id, geometry] : geometries) {
    if (!use(pair_id)) continue;
    const uint32_t offset1 = index.offset.at(geometry.image_id1);
    const uint32_t offset2 = index.offset.at(geometry.image_id2);
    for (const FeatureMatch& match : geometry.inlier_matches) {
      matched[offset1 + match.point2D_idx1] = matched[offset2 + match.point2D_idx2] = true;
      sets.Union(offset1 + match.point2D_idx1, offset2 + match.point2D_idx2);
    }
  }
  // Elements in increasing (image id, keypoint index): each track comes out sorted.
  std::vector<Track> by_root;
  std::vector<int> track_of_root(index.total, -1);
  for (const auto& [image_id, size] : index.size) {
    const uint32_t offset = index.offset.at(image_id);
    for (uint32_t point2D_idx = 0; point2D_idx < size; ++point2D_idx) {
      if (!matched[offset + point2D_idx]) continue;
      int& track = track_of_root[sets.Find(offset + point2D_idx)];
      if (track < 0) {
        track = static_cast<int>(by_root.size());
        by_root.emplace_back();
      }
      by_root[track].push_back({image_id, point2D_idx});
    }
  }

  TrackBuildSummary counts;
  std::vector<Track> tracks;
  for (Track& track : by_root) {
    const bool conflict = std::adjacent_find(track.begin(), track.end(),
                                             [](const TrackElement& a, const TrackElement& b) {
                                               return a.image_id == b.image_id;
                                             }) != track.end();
    if (conflict) {
      ++counts.num_conflicting_tracks;
    } else if (static_cast<int>(track.size()) < options.min_track_length) {
      ++counts.num_short_tracks;
    } else {
      tracks.push_back(std::move(track));
    }
  }
  // Tracks were created in the order of their first element already.
  counts.num_tracks = static_cast<int>(tracks.size());
  if (summary != nullptr) *summary = counts;
  return tracks;
}

}  // namespace ramap
