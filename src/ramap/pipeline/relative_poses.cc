#include "ramap/pipeline/relative_poses.h"

#include "ramap/pipeline/stage_log.h"
#include "ramap/util/parallel.h"

namespace ramap {

bool IsUsableTwoViewConfig(TwoViewConfig config) {
  return config == TwoViewConfig::kCalibrated || config == TwoViewConfig::kUncalibrated ||
         config == TwoViewConfig::kPlanar || config == TwoViewConfig::kPlanarOrPanoramic;
}

std::vector<ViewGraphEdge> EstimateRelativePoses(const FeatureDatabase& database,
                                                 const ImageBearings& bearings,
                                                 const RelativePoseOptions& options,
                                                 int num_threads, std::ostream* progress) {
  std::vector<ViewGraphEdge> edges;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) {
    if (!IsUsableTwoViewConfig(geometry.config)) continue;
    if (static_cast<int>(geometry.inlier_matches.size()) < options.min_num_inliers) continue;
    const auto b1 = bearings.bearings.find(geometry.image_id1);
    const auto b2 = bearings.bearings.find(geometry.image_id2);
    if (b1 == bearings.bearings.end() || b2 == bearings.bearings.end()) continue;
    const Camera& camera1 = database.cameras.at(database.images.at(geometry.image_id1).camera_id);
    const Camera& camera2 = database.cameras.at(database.images.at(geometry.image_id2).camera_id);
    const Keypoints& keypoints1 = database.keypoints.at(geometry.image_id1);
    const Keypoints& keypoints2 = database.keypoints.at(geometry.image_id2);
    ViewGraphEdge edge;
    edge.image_id1 = geometry.image_id1;
    edge.image_id2 = geometry.image_id2;
    edge.num_verified_matches = static_cast<int>(geometry.inlier_matches.size());
    TwoViewCorrespondences& c = edge.correspondences;
    c.width1 = static_cast<int>(camera1.width);
    c.height1 = static_cast<int>(camera1.height);
    c.width2 = static_cast<int>(camera2.width);
    c.height2 = static_cast<int>(camera2.height);
    c.focal_length_px = 0.5 * (bearings.focal_lengths_px.at(camera1.camera_id) +
                               bearings.focal_lengths_px.at(camera2.camera_id));
    const bool use_ratios = options.use_descriptor_ratios && !geometry.inlier_ratios.empty();
    for (size_t k = 0; k < geometry.inlier_matches.size(); ++k) {
      const FeatureMatch& match = geometry.inlier_matches[k];
      // Keypoints past a strong distortion's fold have no bearing (NaN): leave them out.
      if (!b1->second[match.point2D_idx1].allFinite() ||
          !b2->second[match.point2D_idx2].allFinite())
        continue;
      if (use_ratios) c.confidence.push_back(geometry.inlier_ratios[k]);
      c.bearings1.push_back(b1->second[match.point2D_idx1]);
      c.bearings2.push_back(b2->second[match.point2D_idx2]);
      c.pixels1.push_back(keypoints1.xy(match.point2D_idx1));
      c.pixels2.push_back(keypoints2.xy(match.point2D_idx2));
    }
    // Without ramap's descriptor ratios (a COLMAP-matched database), the match confidence for
    // the grid selection is the Sampson error under the F COLMAP stored for every verified pair.
    if (!use_ratios && !geometry.F.isZero()) {
      c.confidence = SampsonErrors(geometry.F, c.pixels1, c.pixels2);
    }
    edges.push_back(std::move(edge));
  }

  ParallelFor(
      edges.size(), num_threads,
      [&](size_t k) {
        edges[k].estimate = EstimateRelativePose(edges[k].correspondences, options);
      },
      progress, stage::kRelativePoses, "pairs");
  return edges;
}

std::vector<RelativePoseRecord> AcceptedRelativePoses(const FeatureDatabase& database,
                                                      const std::vector<ViewGraphEdge>& edges) {
  std::vector<RelativePoseRecord> records;
  for (const ViewGraphEdge& edge : edges) {
    if (!edge.estimate.success) continue;
    records.push_back({database.images.at(edge.image_id1).name,
                       database.images.at(edge.image_id2).name, edge.estimate.rotation,
                       edge.estimate.translation, edge.estimate.num_inliers, edge.estimate.flags});
  }
  return records;
}

}  // namespace ramap
