// Stage 4's tracks: built early over the whole component while its rotations are averaged, and
// used only when rotation averaging kept every edge and image; otherwise built again over the kept
// edges.
#include "ramap/mapper/component_translations.h"

#include <gtest/gtest.h>

#include "ramap/estimators/bearings.h"
#include "ramap/estimators/relative_poses.h"
#include "ramap/mapper/components.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/mapper/mapper_summary.h"
#include "ramap/scene/image_order.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

bool SameTracks(const std::vector<Track>& a, const std::vector<Track>& b) {
  const auto same_element = [](const TrackElement& x, const TrackElement& y) {
    return x.image_id == y.image_id && x.point2D_idx == y.point2D_idx;
  };
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k) {
    if (!std::equal(a[k].begin(), a[k].end(), b[k].begin(), b[k].end(), same_element)) return false;
  }
  return true;
}

// Everything a pass's input refers to, for a noise-free 20-frame line with the true rotations.
class TranslationStage : public ::testing::TestWithParam<int> {
 protected:
  TranslationStage()
      : scene_(BuildSyntheticScene(
            test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 20))),
        options_(test::AveragingOnly()),
        bearings_(ComputeBearings(scene_.database, "synthetic")),
        pairs_(EstimateRelativePoses(scene_.database, bearings_, options_.relative_pose, 1)),
        order_(ImageIdsInCaptureOrder(scene_.database)) {
    options_.num_threads = GetParam();
    graph_ = RotationGraphOfAcceptedPairs(scene_.database, pairs_, &report_);
    for (const auto& [id, image] : scene_.ground_truth.images)
      rotations_[id] = image.cam_from_world.rotation;
  }

  PassInput Input() const {
    return PassInput{
        scene_.database, options_, scene_.database.cameras, bearings_, pairs_, order_, true,
        priors_};
  }

  // Stage 4 as the mapper runs it: the early tracks started over the whole graph, then
  // translation averaging of what `status` keeps.
  std::optional<ComponentTranslations> Translate(const std::vector<EdgeStatus>& status) {
    const PassInput input = Input();
    ComponentState state;
    state.graph = graph_;
    state.early_tracks = StartComponentTracks(input, state.graph);
    state.rotations = rotations_;
    state.edge_status = status;
    return AverageComponentTranslations(input, std::move(state)).translations;
  }

  // The tracks of the graph's edges that `status` keeps.
  std::vector<Track> TracksOfKept(const std::vector<EdgeStatus>& status) const {
    std::set<uint64_t> pair_ids;
    for (size_t e = 0; e < graph_.edges.size(); ++e) {
      const ImagePair& pair = pairs_[graph_.edges[e].pair_index];
      if (status[e] == EdgeStatus::kKept)
        pair_ids.insert(ImagePairToPairId(pair.image_id1, pair.image_id2));
    }
    return BuildTracks(scene_.database.two_view_geometries, pair_ids);
  }

  SyntheticScene scene_;
  MapperOptions options_;
  ImageBearings bearings_;
  std::vector<ImagePair> pairs_;
  std::vector<uint32_t> order_;
  StageReport report_;
  PosePriors priors_;
  RotationGraph graph_;
  std::map<uint32_t, Eigen::Quaterniond> rotations_;
};

TEST_P(TranslationStage, EarlyTracksServeWhenEveryEdgeIsKept) {
  const std::vector<EdgeStatus> status(graph_.edges.size(), EdgeStatus::kKept);
  const std::optional<ComponentTranslations> translations = Translate(status);
  ASSERT_TRUE(translations);
  EXPECT_TRUE(translations->tracks_built_early);
  EXPECT_TRUE(SameTracks(translations->tracks, TracksOfKept(status)));
  EXPECT_EQ(translations->positions.centers.size(), 20u);
}

// The last frame cut off, as rotation averaging leaves a frame whose edges it pruned: its
// matches must not join the tracks.
TEST_P(TranslationStage, TracksAreBuiltAgainOverTheKeptEdgesWhenEdgesArePruned) {
  const uint32_t last = order_.back();
  std::vector<EdgeStatus> status(graph_.edges.size(), EdgeStatus::kKept);
  for (size_t e = 0; e < graph_.edges.size(); ++e) {
    const ImagePair& pair = pairs_[graph_.edges[e].pair_index];
    if (pair.image_id1 == last || pair.image_id2 == last)
      status[e] = EdgeStatus::kPrunedDisconnected;
  }
  rotations_.erase(last);
  const std::vector<Track> kept_tracks = TracksOfKept(status);
  const std::vector<EdgeStatus> all_kept(graph_.edges.size(), EdgeStatus::kKept);
  ASSERT_FALSE(SameTracks(kept_tracks, TracksOfKept(all_kept)));

  const std::optional<ComponentTranslations> translations = Translate(status);
  ASSERT_TRUE(translations);
  EXPECT_FALSE(translations->tracks_built_early);
  EXPECT_TRUE(SameTracks(translations->tracks, kept_tracks));
  for (const Track& track : translations->tracks) {
    for (const TrackElement& element : track) EXPECT_NE(element.image_id, last);
  }
  EXPECT_EQ(translations->positions.centers.size(), 19u);
}

// With one thread the early tracks are built when first asked for; with two, beside the rotations.
INSTANTIATE_TEST_SUITE_P(Threads, TranslationStage, ::testing::Values(1, 2));

}  // namespace
}  // namespace ramap
