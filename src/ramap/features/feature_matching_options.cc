#include <string>
#include <utility>
#include <vector>

#include "ramap/features/feature_matching.h"

namespace ramap {

namespace {

using Table = OptionTable<FeatureMatchingOptions>;

void DeclarePart1(Table& t) {
  t.push_back(ChoiceOption<FeatureMatchingOptions>(
      "Matching.mode", [](auto& o) -> auto& { return o.mode; },
      std::vector<std::pair<std::string, MatchingMode>>{{"auto", MatchingMode::kAuto},
                                                        {"sequential", MatchingMode::kSequential},
                                                        {"exhaustive", MatchingMode::kExhaustive},
                                                        {"retrieval", MatchingMode::kRetrieval}},
      "auto: every pair up to auto_exhaustive_max_images images, else sequential for "
      "frame-numbered names, else retrieval"));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.auto_exhaustive_max_images",
      [](auto& o) -> auto& { return o.auto_exhaustive_max_images; }, AtLeast(0),
      "auto: every pair up to this many images"));
  t.push_back(ColmapNamed(NumberOption<FeatureMatchingOptions>(
                              "Matching.overlap", [](auto& o) -> auto& { return o.overlap; },
                              AtLeast(1), "sequential: each image with its next N"),
                          {"SequentialMatching.overlap"}));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.loop_num_neighbors", [](auto& o) -> auto& { return o.loop_num_neighbors; },
      AtLeast(0),
      "sequential: each frame also with its N most similar frames (image "
      "retrieval) at least loop_min_frame_gap frames away (0: none)"));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.loop_min_frame_gap", [](auto& o) -> auto& { return o.loop_min_frame_gap; },
      AtLeast(0), "sequential: loop candidates are at least this many frames apart"));
  t.push_back(ColmapNamed(NumberOption<FeatureMatchingOptions>(
                              "Matching.retrieval_num_neighbors",
                              [](auto& o) -> auto& { return o.retrieval_num_neighbors; },
                              AtLeast(1), "retrieval: each image with its N most similar images"),
                          {"VocabTreeMatching.num_images"}));
  t.push_back(ColmapNamed(NumberOption<FeatureMatchingOptions>(
                              "Matching.max_ratio", [](auto& o) -> auto& { return o.max_ratio; },
                              OptionRange{0, true, 1, false}, "Lowe's ratio test"),
                          {"SiftMatching.max_ratio"}));
  t.push_back(
      ColmapNamed(BoolOption<FeatureMatchingOptions>(
                      "Matching.cross_check", [](auto& o) -> auto& { return o.cross_check; },
                      "1: keep mutual nearest neighbours only"),
                  {"SiftMatching.cross_check"}));
}

void DeclarePart2(Table& t) {
  t.push_back(
      ColmapNamed(NumberOption<FeatureMatchingOptions>(
                      "Matching.max_error_px", [](auto& o) -> auto& { return o.max_error_px; },
                      Above(0), "verification's epipolar inlier threshold, pixels"),
                  {"SiftMatching.max_error", "TwoViewGeometry.max_error"}));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.confidence", [](auto& o) -> auto& { return o.confidence; }, Above(0, 1),
      "verification's RANSAC confidence"));
  t.push_back(ColmapNamed(
      NumberOption<FeatureMatchingOptions>(
          "Matching.min_num_inliers", [](auto& o) -> auto& { return o.min_num_inliers; },
          AtLeast(5), "pairs with fewer verified matches are dropped"),
      {"SiftMatching.min_num_inliers", "TwoViewGeometry.min_num_inliers"}));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.preemptive_num_features",
      [](auto& o) -> auto& { return o.preemptive_num_features; }, AtLeast(0),
      "exhaustive: match the N largest-scale features first, full matching only "
      "for pairs with enough matches among them (0: off)"));
  t.push_back(NumberOption<FeatureMatchingOptions>(
      "Matching.preemptive_min_matches", [](auto& o) -> auto& { return o.preemptive_min_matches; },
      AtLeast(1), "matches among those features a pair needs"));
  t.push_back(
      ColmapNamed(NumberOption<FeatureMatchingOptions>(
                      "Matching.num_threads", [](auto& o) -> auto& { return o.num_threads; },
                      AtLeast(1, 256), "pairs matched at once"),
                  {"SiftMatching.num_threads", "FeatureMatching.num_threads"}));
}

}  // namespace

const OptionTable<FeatureMatchingOptions>& FeatureMatchingOptionTable() {
  static const Table table = [] {
    Table t;
    DeclarePart1(t);
    DeclarePart2(t);
    AppendOptions(
        ImageRetrievalOptionTable(), [](auto& o) -> auto& { return o.retrieval; }, &t);
    // COLMAP's options of this step that have no meaning here.
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>("SiftMatching.use_gpu",
                                                            "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>("SiftMatching.gpu_index",
                                                            "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>("FeatureMatching.use_gpu",
                                                            "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>("FeatureMatching.gpu_index",
                                                            "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>(
        "ExhaustiveMatching.block_size", "ramap screens and matches every pair in one pass"));
    t.push_back(IgnoredColmapOption<FeatureMatchingOptions>(
        "VocabTreeMatching.vocab_tree_path",
        "ramap trains its retrieval vocabulary on the images' own descriptors"));
    return t;
  }();
  return table;
}

}  // namespace ramap
