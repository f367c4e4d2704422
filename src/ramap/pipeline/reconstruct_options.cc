#include "ramap/pipeline/reconstruct_options.h"

#include <stdexcept>

#include "ramap/pipeline/mapper_option_table.h"
#include "ramap/util/error.h"

namespace ramap {

namespace {

using FeatureTable = OptionTable<FeatureOptions>;

template <typename Access>
OptionDeclaration<FeatureOptions> Number(std::string name, Access access, OptionRange range,
                                         std::string help = "") {
  return NumberOption<FeatureOptions>(std::move(name), access, range, std::move(help));
}

// COLMAP's version names as DatabaseGenerationFromName reads them (3.9, 4.x, 4.1.1, ...): a
// choice of three schemas under many names.
OptionDeclaration<FeatureOptions> DatabaseGenerationOption() {
  OptionDeclaration<FeatureOptions> d;
  d.name = "Database.generation";
  d.type = OptionType::kText;
  d.choices = {"3.8", "3.10", "4"};
  d.help =
      "schema of the new database: 3.8 (COLMAP 3.8-3.9, read by every COLMAP), 3.10 "
      "(3.10-3.11) or 4 (3.12-4.x)";
  d.check = [](const std::string& text) -> std::string {
    try {
      DatabaseGenerationFromName(text, "--Database.generation");
    } catch (const InputError&) {
      return "'" + text + "' is not 3.8, 3.10 or 4 (COLMAP 3.8-3.9, 3.10-3.11, 3.12-4.x)";
    }
    return "";
  };
  d.text = [](const FeatureOptions& o) -> std::string {
    return o.generation == DatabaseGeneration::kColmap38    ? "3.8"
           : o.generation == DatabaseGeneration::kColmap310 ? "3.10"
                                                            : "4";
  };
  d.json = [text = d.text](const FeatureOptions& o) -> nlohmann::json { return text(o); };
  d.store = [](FeatureOptions& o, const std::string& text) {
    o.generation = DatabaseGenerationFromName(text, "--Database.generation");
  };
  return d;
}

FeatureTable BuildExtractionTable() {
  FeatureTable t;
  t.push_back(TextOption<FeatureOptions>(
      "ImageReader.camera_model", [](auto& o) -> auto& { return o.reader.camera_model; },
      "COLMAP camera model"));
  t.push_back(TextOption<FeatureOptions>(
      "ImageReader.camera_params", [](auto& o) -> auto& { return o.reader.camera_params; },
      "known intrinsics at full resolution, e.g. fx,fy,cx,cy for PINHOLE (empty: EXIF or the "
      "default focal length)"));
  t.push_back(BoolOption<FeatureOptions>(
      "ImageReader.single_camera", [](auto& o) -> auto& { return o.reader.single_camera; },
      "1: one camera for all images"));
  t.push_back(Number(
      "ImageReader.default_focal_length_factor",
      [](auto& o) -> auto& { return o.reader.default_focal_length_factor; }, Above(0),
      "focal length guess, times the longest side, without camera_params"));
  t.push_back(ChoiceOption<FeatureOptions>(
      "FeatureExtraction.type", [](auto& o) -> auto& { return o.extraction.type; },
      std::vector<std::pair<std::string, FeatureType>>{{"sift", FeatureType::kSift},
                                                       {"orb", FeatureType::kOrb}},
      "OpenCV's SIFT or ORB"));
  t.push_back(Number(
      "FeatureExtraction.max_image_size",
      [](auto& o) -> auto& { return o.extraction.max_image_size; }, AtLeast(32),
      "images are scaled down to this longest side first"));
  t.push_back(Number(
      "FeatureExtraction.max_num_features",
      [](auto& o) -> auto& { return o.extraction.max_num_features; }, AtLeast(16),
      "features per image at most"));
  t.push_back(Number(
      "FeatureExtraction.num_threads", [](auto& o) -> auto& { return o.reader.num_threads; },
      AtLeast(1, 256), "images read and described at once"));
  t.push_back(DatabaseGenerationOption());
  return t;
}

void AddMatchingPlan(FeatureTable& t) {
  t.push_back(ChoiceOption<FeatureOptions>(
      "Matching.mode", [](auto& o) -> auto& { return o.matching.mode; },
      std::vector<std::pair<std::string, MatchingMode>>{{"auto", MatchingMode::kAuto},
                                                        {"sequential", MatchingMode::kSequential},
                                                        {"exhaustive", MatchingMode::kExhaustive},
                                                        {"retrieval", MatchingMode::kRetrieval}},
      "auto: every pair up to auto_exhaustive_max_images images, else sequential for "
      "frame-numbered names, else retrieval"));
  t.push_back(Number(
      "Matching.auto_exhaustive_max_images",
      [](auto& o) -> auto& { return o.matching.auto_exhaustive_max_images; }, AtLeast(0),
      "auto: every pair up to this many images"));
  t.push_back(Number(
      "Matching.overlap", [](auto& o) -> auto& { return o.matching.overlap; }, AtLeast(1),
      "sequential: each image with its next N"));
  t.push_back(Number(
      "Matching.loop_num_neighbors", [](auto& o) -> auto& { return o.matching.loop_num_neighbors; },
      AtLeast(0),
      "sequential: each frame also with its N most similar frames (image "
      "retrieval) at least loop_min_frame_gap frames away (0: none)"));
  t.push_back(Number(
      "Matching.loop_min_frame_gap", [](auto& o) -> auto& { return o.matching.loop_min_frame_gap; },
      AtLeast(0), "sequential: loop candidates are at least this many frames apart"));
  t.push_back(Number(
      "Matching.retrieval_num_neighbors",
      [](auto& o) -> auto& { return o.matching.retrieval_num_neighbors; }, AtLeast(1),
      "retrieval: each image with its N most similar images"));
  t.push_back(Number(
      "Matching.retrieval_num_words",
      [](auto& o) -> auto& { return o.matching.retrieval.num_words; }, AtLeast(1),
      "visual words of the vocabulary trained on the images' own descriptors"));
  t.push_back(Number(
      "Matching.retrieval_max_features_per_image",
      [](auto& o) -> auto& { return o.matching.retrieval.max_features_per_image; }, AtLeast(1),
      "the largest-scale descriptors of an image that describe it for retrieval"));
  t.push_back(Number(
      "Matching.retrieval_max_training_descriptors",
      [](auto& o) -> auto& { return o.matching.retrieval.max_training_descriptors; }, AtLeast(1),
      "descriptors the vocabulary is trained on at most"));
  t.push_back(Number(
      "Matching.retrieval_num_kmeans_iterations",
      [](auto& o) -> auto& { return o.matching.retrieval.num_kmeans_iterations; }, AtLeast(0),
      "k-means iterations of the vocabulary"));
}

FeatureTable BuildMatchingTable() {
  FeatureTable t;
  AddMatchingPlan(t);
  t.push_back(Number(
      "Matching.max_ratio", [](auto& o) -> auto& { return o.matching.max_ratio; },
      OptionRange{0, true, 1, false}, "Lowe's ratio test"));
  t.push_back(BoolOption<FeatureOptions>(
      "Matching.cross_check", [](auto& o) -> auto& { return o.matching.cross_check; },
      "1: keep mutual nearest neighbours only"));
  t.push_back(Number(
      "Matching.max_error_px", [](auto& o) -> auto& { return o.matching.max_error_px; }, Above(0),
      "verification's epipolar inlier threshold, pixels"));
  t.push_back(Number(
      "Matching.confidence", [](auto& o) -> auto& { return o.matching.confidence; }, Above(0, 1),
      "verification's RANSAC confidence"));
  t.push_back(Number(
      "Matching.min_num_inliers", [](auto& o) -> auto& { return o.matching.min_num_inliers; },
      AtLeast(5), "pairs with fewer verified matches are dropped"));
  t.push_back(Number(
      "Matching.preemptive_num_features",
      [](auto& o) -> auto& { return o.matching.preemptive_num_features; }, AtLeast(0),
      "exhaustive: match the N largest-scale features first, full matching only "
      "for pairs with enough matches among them (0: off)"));
  t.push_back(Number(
      "Matching.preemptive_min_matches",
      [](auto& o) -> auto& { return o.matching.preemptive_min_matches; }, AtLeast(1),
      "matches among those features a pair needs"));
  t.push_back(Number(
      "Matching.num_threads", [](auto& o) -> auto& { return o.matching.num_threads; },
      AtLeast(1, 256), "pairs matched at once"));
  return t;
}

void AddLoopClosure(OptionTable<ReconstructOptions>& t) {
  t.push_back(BoolOption<ReconstructOptions>(
      "LoopClosure.enable", [](auto& o) -> auto& { return o.close_loops; },
      "1: after sequential matching, match the pairs a first solve puts close, solve again"));
  t.push_back(NumberOption<ReconstructOptions>(
      "LoopClosure.max_distance_baselines",
      [](auto& o) -> auto& { return o.loop_closure.candidates.max_distance_baselines; }, Above(0),
      "candidate centres within this many median frame-to-frame baselines"));
  t.push_back(NumberOption<ReconstructOptions>(
      "LoopClosure.max_view_angle_deg",
      [](auto& o) -> auto& { return o.loop_closure.candidates.max_view_angle_deg; },
      OptionRange{0, true, 180, false}, "candidates look at most this far apart"));
  t.push_back(NumberOption<ReconstructOptions>(
      "LoopClosure.min_frame_gap",
      [](auto& o) -> auto& { return o.loop_closure.candidates.min_frame_gap; }, AtLeast(2),
      "candidates are at least this many frames apart"));
  t.push_back(NumberOption<ReconstructOptions>(
      "LoopClosure.max_candidates_per_image",
      [](auto& o) -> auto& { return o.loop_closure.candidates.max_candidates_per_image; },
      AtLeast(1), "candidates per image at most"));
  t.push_back(NumberOption<ReconstructOptions>(
      "LoopClosure.max_bridge_pairs",
      [](auto& o) -> auto& { return o.loop_closure.max_bridge_pairs; }, AtLeast(0),
      "when the first solve splits, pairs between two models screened to join them (0: off)"));
}

OptionTable<ReconstructOptions> BuildReconstructTable() {
  OptionTable<ReconstructOptions> t;
  const auto features = [](auto& o) -> auto& { return o.features; };
  AppendOptions(ExtractionOptionTable(), features, &t);
  AppendOptions(MatchingOptionTable(), features, &t);
  AppendOptions(
      MapperOptionTable(), [](auto& o) -> auto& { return o.mapper; }, &t);
  AddLoopClosure(t);
  return t;
}

}  // namespace

const OptionTable<FeatureOptions>& ExtractionOptionTable() {
  static const FeatureTable table = BuildExtractionTable();
  return table;
}

const OptionTable<FeatureOptions>& MatchingOptionTable() {
  static const FeatureTable table = BuildMatchingTable();
  return table;
}

const OptionTable<ReconstructOptions>& ReconstructOptionTable() {
  static const OptionTable<ReconstructOptions> table = BuildReconstructTable();
  return table;
}

void ResolveFeatureOptions(FeatureOptions* options) {
  CheckOptionValues(ExtractionOptionTable(), *options);
  CheckOptionValues(MatchingOptionTable(), *options);
  options->reader.Check();
  options->extraction.Check();
  options->matching.Check();
}

void ResolveReconstructOptions(ReconstructOptions* options) {
  // Each part checked once, by its own resolver; loop closure's ranges are its struct's.
  ResolveFeatureOptions(&options->features);
  ResolveMapperOptions(&options->mapper);
  options->loop_closure.Check();
}

}  // namespace ramap
