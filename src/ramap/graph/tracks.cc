#include "ramap/graph/tracks.h"

#include <algorithm>
#include <unordered_map>

namespace ramap {
namespace {

uint64_t Key(uint32_t image_id, uint32_t point2D_idx) {
  return (static_cast<uint64_t>(image_id) << 32) | point2D_idx;
}

class DisjointSets {
 public:
  uint64_t Find(uint64_t x) {
    auto [it, inserted] = parent_.try_emplace(x, x);
    if (inserted || it->second == x) return x;
    const uint64_t root = Find(it->second);
    parent_[x] = root;
    return root;
  }
  void Union(uint64_t a, uint64_t b) {
    const uint64_t ra = Find(a), rb = Find(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }
  const std::unordered_map<uint64_t, uint64_t>& elements() const { return parent_; }

 private:
  std::unordered_map<uint64_t, uint64_t> parent_;
};

}  // namespace

std::vector<Track> BuildTracks(const std::map<uint64_t, TwoViewGeometry>& geometries,
                               const std::set<uint64_t>& use_pairs,
                               const TrackBuildOptions& options, TrackBuildSummary* summary) {
  DisjointSets sets;
  for (const auto& [pair_id, geometry] : geometries) {
    if (!use_pairs.empty() && !use_pairs.count(pair_id)) continue;
    for (const FeatureMatch& match : geometry.inlier_matches) {
      sets.Union(Key(geometry.image_id1, match.point2D_idx1),
                 Key(geometry.image_id2, match.point2D_idx2));
    }
  }
  std::unordered_map<uint64_t, Track> by_root;
  std::vector<uint64_t> keys;
  keys.reserve(sets.elements().size());
  for (const auto& [key, parent] : sets.elements()) keys.push_back(key);
  for (const uint64_t key : keys) {
    by_root[sets.Find(key)].push_back(
        {static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key & 0xffffffffu)});
  }

  TrackBuildSummary counts;
  std::vector<Track> tracks;
  for (auto& [root, track] : by_root) {
    std::sort(track.begin(), track.end(), [](const TrackElement& a, const TrackElement& b) {
      return a.image_id != b.image_id ? a.image_id < b.image_id : a.point2D_idx < b.point2D_idx;
    });
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
  std::sort(tracks.begin(), tracks.end(), [](const Track& a, const Track& b) {
    return std::make_pair(a[0].image_id, a[0].point2D_idx) <
           std::make_pair(b[0].image_id, b[0].point2D_idx);
  });
  counts.num_tracks = static_cast<int>(tracks.size());
  if (summary != nullptr) *summary = counts;
  return tracks;
}

}  // namespace ramap
