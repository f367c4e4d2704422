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

ObservationIndex IndexObservations(const std::vector<const TwoViewGeometry*>& pairs) {
  ObservationIndex index;
  for (const TwoViewGeometry* geometry : pairs) {
    uint32_t& size1 = index.size[geometry->image_id1];
    uint32_t& size2 = index.size[geometry->image_id2];
    for (const FeatureMatch& match : geometry->inlier_matches) {
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

// The observations' sets after uniting every match, and which observations are matched.
struct MatchedSets {
  explicit MatchedSets(uint32_t size) : sets(size), matched(size, 0) {}
  DisjointSets sets;
  std::vector<uint8_t> matched;
};

// Every match of the pairs united.
MatchedSets UniteMatches(const std::vector<const TwoViewGeometry*>& pairs,
                         const ObservationIndex& index) {
  MatchedSets united(index.total);
  for (const TwoViewGeometry* geometry : pairs) {
    const uint32_t offset1 = index.offset.at(geometry->image_id1);
    const uint32_t offset2 = index.offset.at(geometry->image_id2);
    for (const FeatureMatch& match : geometry->inlier_matches) {
      united.matched[offset1 + match.point2D_idx1] = 1;
      united.matched[offset2 + match.point2D_idx2] = 1;
      united.sets.Union(offset1 + match.point2D_idx1, offset2 + match.point2D_idx2);
    }
  }
  return united;
}

// One track per set of matched observations, in the order of their smallest observation; each
// track's elements in increasing (image id, keypoint index).
std::vector<Track> GatherTracks(const MatchedSets& united, const ObservationIndex& index) {
  const std::vector<uint32_t> roots = united.sets.Roots();
  // A set's root is its smallest element, so it is met before the set's other elements.
  std::vector<int> track_of_root(index.total, -1);
  std::vector<uint32_t> track_sizes;
  for (uint32_t x = 0; x < index.total; ++x) {
    if (!united.matched[x]) continue;
    if (roots[x] == x) {
      track_of_root[x] = static_cast<int>(track_sizes.size());
      track_sizes.push_back(0);
    }
    ++track_sizes[track_of_root[roots[x]]];
  }
  std::vector<Track> tracks(track_sizes.size());
  for (size_t t = 0; t < tracks.size(); ++t) tracks[t].reserve(track_sizes[t]);
  for (const auto& [image_id, size] : index.size) {
    const uint32_t offset = index.offset.at(image_id);
    for (uint32_t point2D_idx = 0; point2D_idx < size; ++point2D_idx) {
      if (!united.matched[offset + point2D_idx]) continue;
      tracks[track_of_root[roots[offset + point2D_idx]]].push_back({image_id, point2D_idx});
    }
  }
  return tracks;
}

}  // namespace

std::vector<Track> BuildTracks(const std::map<uint64_t, TwoViewGeometry>& geometries,
                               const std::set<uint64_t>& use_pairs,
                               const TrackBuildOptions& options, TrackBuildSummary* summary) {
  const auto use = [&](uint64_t pair_id) { return use_pairs.empty() || use_pairs.count(pair_id); };
  std::vector<const TwoViewGeometry*> pairs;
  for (const auto& [pair_id, geometry] : geometries) {
    if (use(pair_id)) pairs.push_back(&geometry);
  }
  const ObservationIndex index = IndexObservations(pairs);
  std::vector<Track> by_root = GatherTracks(UniteMatches(pairs, index), index);

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
  // Tracks were gathered in the order of their first element already.
  counts.num_tracks = static_cast<int>(tracks.size());
  if (summary != nullptr) *summary = counts;
  return tracks;
}

}  // namespace ramap
