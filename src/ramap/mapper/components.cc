#include "ramap/mapper/components.h"

#include <algorithm>
#include <numeric>
#include <set>
#include <unordered_map>

#include "ramap/graph/rigid_clusters.h"
#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/graph/tracks.h"
#include "ramap/mapper/mapper_state.h"

namespace ramap {

RotationGraph RotationGraphOfAcceptedPairs(const FeatureDatabase& database,
                                           const std::vector<ImagePair>& pairs,
                                           StageReport* report) {
  RotationGraph graph = AcceptedRotationGraph(pairs);
  const std::set<uint32_t> nodes(graph.node_ids.begin(), graph.node_ids.end());
  for (const ImagePair& pair : pairs) {
    if (pair.accepted()) continue;
    report->dropped_edges.push_back({PairName(database, pair.image_id1, pair.image_id2),
                                     "relative pose rejected: " + pair.estimate.reason});
    for (const uint32_t id : {pair.image_id1, pair.image_id2}) {
      if (!nodes.count(id))
        report->image_reasons[id] = "every relative pose rejected (" + pair.estimate.reason + ")";
    }
  }
  return graph;
}

namespace {

// Tracks that a join through one image (`hub`) leaves joined: some track must see an image of
// each cluster besides the hub, or nothing fixes their relative scale. A few wrong matches can
// make a track or two; a shared scene makes many.
constexpr int kMinSpanningTracks = 10;

int Find(std::vector<int>& parent, int k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

// How many of `tracks` see an image of `side1` and one of `side2`, the hub aside.
int SpanningTracks(const std::vector<Track>& tracks, const std::set<uint32_t>& side1,
                   const std::set<uint32_t>& side2, uint32_t hub) {
  int count = 0;
  for (const Track& track : tracks) {
    bool in1 = false, in2 = false;
    for (const TrackElement& element : track) {
      if (element.image_id == hub) continue;
      in1 = in1 || side1.count(element.image_id);
      in2 = in2 || side2.count(element.image_id);
    }
    count += in1 && in2;
  }
  return count;
}

// Images in no cluster (group -1) join the group most of their pairs reach, in passes until each
// that a pair links to a group has one.
void AssignImagesInNoCluster(const RotationGraph& component,
                             const std::unordered_map<uint32_t, int>& index,
                             std::vector<int>* group) {
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::map<int, int>> votes(group->size());
    for (const RelativeRotationEdge& edge : component.edges) {
      const int a = index.at(edge.i), b = index.at(edge.j);
      if ((*group)[a] < 0 && (*group)[b] >= 0) ++votes[a][(*group)[b]];
      if ((*group)[b] < 0 && (*group)[a] >= 0) ++votes[b][(*group)[a]];
    }
    for (size_t k = 0; k < group->size(); ++k) {
      if ((*group)[k] >= 0 || votes[k].empty()) continue;
      (*group)[k] =
          std::max_element(votes[k].begin(), votes[k].end(), [](const auto& x, const auto& y) {
            return x.second < y.second;
          })->first;
      changed = true;
    }
  }
}

// `component` cut where two of its clusters are joined through one image and no track spans the
// join (graph/rigid_clusters.h): nothing fixes one's scale against the other's, and averaged as
// one they would force photos of something else into the scene's model. Each group of clusters
// still joined is a component; an image in no cluster goes with the group most of its pairs reach.
// The pairs cut are reported with the reason.
std::vector<RotationGraph> SplitAtScaleFreeJoins(const RotationGraph& component,
                                                 const FeatureDatabase& database,
                                                 StageReport* report) {
  const std::vector<int> clusters = TriangleClusters(component);
  const int num_clusters =
      clusters.empty() ? 0 : *std::max_element(clusters.begin(), clusters.end()) + 1;
  if (num_clusters <= 1) return {component};
  std::vector<int> parent(num_clusters);
  std::iota(parent.begin(), parent.end(), 0);
  const std::vector<ClusterJoin> joins = ClusterJoins(component, clusters);
  std::vector<Track> tracks;
  bool tracks_built = false;
  std::vector<std::set<uint32_t>> members(num_clusters);
  for (size_t k = 0; k < clusters.size(); ++k)
    if (clusters[k] >= 0) members[clusters[k]].insert(component.node_ids[k]);
  for (const ClusterJoin& join : joins) {
    bool joined = !join.through_one_image();
    if (!joined) {
      if (!tracks_built) {
        std::set<uint64_t> pair_ids;
        for (const RelativeRotationEdge& edge : component.edges)
          pair_ids.insert(ImagePairToPairId(edge.i, edge.j));
        tracks = BuildTracks(database.two_view_geometries, pair_ids);
        tracks_built = true;
      }
      const uint32_t hub = join.images1.size() == 1 ? join.images1[0] : join.images2[0];
      joined = SpanningTracks(tracks, members[join.cluster1], members[join.cluster2], hub) >=
               kMinSpanningTracks;
    }
    if (joined) parent[Find(parent, join.cluster1)] = Find(parent, join.cluster2);
  }
  std::vector<int> group(clusters.size(), -1);
  for (size_t k = 0; k < clusters.size(); ++k)
    if (clusters[k] >= 0) group[k] = Find(parent, clusters[k]);
  std::set<int> groups(group.begin(), group.end());
  groups.erase(-1);
  if (groups.size() <= 1) return {component};
  const std::unordered_map<uint32_t, int> index = NodeIndex(component);
  AssignImagesInNoCluster(component, index, &group);
  for (int& label : group)
    if (label < 0) label = *groups.begin();
  RotationGraph uncut = component;
  uncut.edges.clear();
  for (const RelativeRotationEdge& edge : component.edges) {
    if (group[index.at(edge.i)] == group[index.at(edge.j)]) {
      uncut.edges.push_back(edge);
      continue;
    }
    report->dropped_edges.push_back(
        {PairName(database, edge.i, edge.j),
         "joins two parts of the view graph through one image, with no track seen on both sides: "
         "their relative scale is free (photos of something else, joined by one that shows "
         "both?)"});
  }
  // Labels in decreasing group size, as ComponentSubgraphs expects them.
  std::map<int, int> sizes;
  for (const int label : group) ++sizes[label];
  std::vector<int> order;
  for (const auto& [label, size] : sizes) order.push_back(label);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return sizes.at(a) > sizes.at(b); });
  std::map<int, int> rank;
  for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<int>(k);
  for (int& label : group) label = rank.at(label);
  return ComponentSubgraphs(uncut, group);
}

}  // namespace

std::vector<RotationGraph> ComponentsToReconstruct(const RotationGraph& graph, int min_size,
                                                   const FeatureDatabase& database,
                                                   StageReport* report) {
  std::vector<RotationGraph> kept;
  for (RotationGraph& connected : ComponentSubgraphs(graph, ConnectedComponents(graph))) {
    for (RotationGraph& component : SplitAtScaleFreeJoins(connected, database, report)) {
      const int size = static_cast<int>(component.node_ids.size());
      if (size >= min_size) {
        kept.push_back(std::move(component));
        continue;
      }
      for (const uint32_t id : component.node_ids) {
        report->image_reasons[id] = "in a component of " + std::to_string(size) +
                                    " images (< Mapper.min_component_size " +
                                    std::to_string(min_size) + ")";
      }
    }
  }
  // Largest first, across the components the cuts made.
  std::stable_sort(kept.begin(), kept.end(), [](const RotationGraph& a, const RotationGraph& b) {
    return a.node_ids.size() > b.node_ids.size();
  });
  return kept;
}

}  // namespace ramap
