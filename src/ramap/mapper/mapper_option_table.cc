#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "ramap/mapper/mapper_options.h"

namespace ramap {

namespace {

using Declaration = OptionDeclaration<MapperOptions>;
using Table = OptionTable<MapperOptions>;

template <typename Access>
Declaration Number(std::string name, Access access, OptionRange range, std::string help = "") {
  return NumberOption<MapperOptions>(std::move(name), access, range, std::move(help));
}

template <typename Access>
Declaration Bool(std::string name, Access access, std::string help = "") {
  return BoolOption<MapperOptions>(std::move(name), access, std::move(help));
}

template <typename Value, typename Access>
Declaration Choice(std::string name, Access access,
                   std::vector<std::pair<std::string, Value>> names, std::string help) {
  return ChoiceOption<MapperOptions>(std::move(name), access, std::move(names), std::move(help));
}

// "auto", "1" and "0" as three values of an enum.
template <typename Value>
std::vector<std::pair<std::string, Value>> AutoOnOff(Value when_auto, Value when_on,
                                                     Value when_off) {
  return {{"auto", when_auto}, {"1", when_on}, {"0", when_off}};
}

// The mapper's own settings: how the stages are chained, not how any one of them works.
void DeclareOrderAndWeights(Table& t) {
  t.push_back(Number(
      "Mapper.num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1, 256),
      "threads of every stage (bundle adjustment and the BLAS included)"));
  t.push_back(FormerlyNamed(
      Choice(
          "ViewGraph.sequential", [](auto& o) -> auto& { return o.order; },
          AutoOnOff(InputOrder::kAuto, InputOrder::kSequential, InputOrder::kUnordered),
          "keyframe windows for sequences (1), one view graph for collections (0)"),
      "PoseGraph.sequential"));
  t.push_back(Choice(
      "RotationAveraging.edge_weights", [](auto& o) -> auto& { return o.rotation_edge_weights; },
      AutoOnOff(EdgeWeighting::kAuto, EdgeWeighting::kOn, EdgeWeighting::kOff),
      "weight edges by their inlier counts (auto: when every camera's focal "
      "length is known)"));
  t.push_back(Bool(
      "RotationAveraging.fold_check", [](auto& o) -> auto& { return o.rotation_fold_check; },
      "1: unweighted, average again with inlier-count weights and keep that solution where the "
      "two differ grossly and it leaves out fewer inliers (a fold along symmetric structure)"));
  t.push_back(Number(
      "RotationAveraging.fold_min_difference_deg",
      [](auto& o) -> auto& { return o.rotation_fold_min_difference_deg; }, AtLeast(0, 180),
      "the difference at some image, degrees, that makes the two solutions disagree"));
  t.push_back(Number(
      "Mapper.min_component_size", [](auto& o) -> auto& { return o.min_component_size; },
      AtLeast(2), "connected components with fewer images are not written"));
}

void DeclareRefinement(Table& t) {
  t.push_back(Bool(
      "Mapper.refine", [](auto& o) -> auto& { return o.refine; },
      "1: bundle adjustment after averaging; 0: no final BA (faster; see "
      "Mapper.subset_adjustment)"));
  t.push_back(Bool(
      "Mapper.subset_adjustment", [](auto& o) -> auto& { return o.subset_adjustment; },
      "with Mapper.refine 0, 1: BA on the Mapper.calibration_num_points longest tracks "
      "only, then every track triangulated again; 0: averaging alone"));
  t.push_back(Number(
      "BundleAdjustment.num_rounds", [](auto& o) -> auto& { return o.num_refinement_rounds; },
      AtLeast(1),
      "rounds of bundle adjustment, each followed by every track triangulated "
      "again"));
}

void DeclareCalibration(Table& t) {
  t.push_back(Number(
      "Mapper.max_focal_change_in_bundle_adjustment",
      [](auto& o) -> auto& { return o.max_focal_change_in_bundle_adjustment; }, AtLeast(0),
      "average again through BA's intrinsics when it moved a focal length by more "
      "(fraction; 0: never), but not one given and proved wrong by the test"));
  t.push_back(Number(
      "Mapper.calibration_num_points", [](auto& o) -> auto& { return o.calibration_num_points; },
      AtLeast(0),
      "points of the first BA when a focal length is still unknown after the view "
      "graph (a second pass follows), and of Mapper.subset_adjustment (0: all)"));
  t.push_back(Number(
      "Mapper.calibration_pass_num_tracks",
      [](auto& o) -> auto& { return o.calibration_pass_num_tracks; }, AtLeast(0),
      "a calibration pass (kept for its intrinsics alone) adjusts at most this many points, "
      "averages translations with at most this many tracks and takes its relative poses "
      "from the five-point solver (0: as the second pass)"));
  t.push_back(Bool(
      "Mapper.calibration_subset_only", [](auto& o) -> auto& { return o.calibration_subset_only; },
      "1: the full BA holds the intrinsics the subset found (0: refines them again)"));
}

// Each stage's options, declared by its own options struct, as parts of MapperOptions.
void AppendStages(Table& t) {
  AppendOptions(
      RelativePoseOptionTable(), [](auto& o) -> auto& { return o.relative_pose; }, &t);
  AppendOptions(
      KeyframeOptionTable(), [](auto& o) -> auto& { return o.view_graph; }, &t);
  AppendOptions(
      RotationAveragingOptionTable(), [](auto& o) -> auto& { return o.rotation_averaging; }, &t);
  AppendOptions(
      TranslationAveragingOptionTable(), [](auto& o) -> auto& { return o.translation_averaging; },
      &t);
  AppendOptions(
      DirectionConsistencyOptionTable(), [](auto& o) -> auto& { return o.direction_consistency; },
      &t);
  AppendOptions(
      WindowedTranslationOptionTable(), [](auto& o) -> auto& { return o.translation_windows; }, &t);
  AppendOptions(
      PairDirectionOptionTable(), [](auto& o) -> auto& { return o.pair_direction; }, &t);
  AppendOptions(
      TrackTriangulationOptionTable(), [](auto& o) -> auto& { return o.triangulation; }, &t);
  AppendOptions(
      ReregistrationOptionTable(), [](auto& o) -> auto& { return o.reregistration; }, &t);
  AppendOptions(
      BundleAdjustmentOptionTable(), [](auto& o) -> auto& { return o.bundle_adjustment; }, &t);
  AppendOptions(
      GivenIntrinsicsTestOptionTable(), [](auto& o) -> auto& { return o.given_intrinsics_test; },
      &t);
  AppendOptions(
      ViewGraphCalibrationOptionTable(), [](auto& o) -> auto& { return o.view_graph_calibration; },
      &t);
  AppendOptions(
      PosePriorSourceOptionTable(), [](auto& o) -> auto& { return o.prior_source; }, &t);
  AppendOptions(
      PriorAlignmentOptionTable(), [](auto& o) -> auto& { return o.prior_alignment; }, &t);
}

Table BuildMapperOptionTable() {
  Table t;
  AppendStages(t);
  DeclareOrderAndWeights(t);
  DeclareRefinement(t);
  DeclareCalibration(t);
  return t;
}

}  // namespace

const OptionTable<MapperOptions>& MapperOptionTable() {
  static const Table table = BuildMapperOptionTable();
  return table;
}

OptionTable<MapperOptions> MapperOptionSections(const std::vector<std::string>& sections,
                                                const std::vector<std::string>& extra) {
  Table subset;
  for (const Declaration& d : MapperOptionTable()) {
    const bool wanted =
        std::find(sections.begin(), sections.end(), d.Section()) != sections.end() ||
        std::find(extra.begin(), extra.end(), d.name) != extra.end();
    if (wanted) subset.push_back(d);
  }
  return subset;
}

}  // namespace ramap
