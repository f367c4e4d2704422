#include "ramap/jobs/reconstruct_options.h"

#include "ramap/mapper/mapper_options.h"

namespace ramap {

namespace {

OptionTable<FeatureOptions> BuildExtractionTable() {
  OptionTable<FeatureOptions> t;
  AppendOptions(
      ImageReaderOptionTable(), [](auto& o) -> auto& { return o.reader; }, &t);
  AppendOptions(
      FeatureExtractionOptionTable(), [](auto& o) -> auto& { return o.extraction; }, &t);
  t.push_back(
      DatabaseGenerationOption<FeatureOptions>([](auto& o) -> auto& { return o.generation; }));
  return t;
}

OptionTable<ReconstructOptions> BuildReconstructTable() {
  OptionTable<ReconstructOptions> t;
  const auto features = [](auto& o) -> auto& { return o.features; };
  AppendOptions(ExtractionOptionTable(), features, &t);
  AppendOptions(MatchingOptionTable(), features, &t);
  AppendOptions(
      MapperOptionTable(), [](auto& o) -> auto& { return o.mapper; }, &t);
  t.push_back(BoolOption<ReconstructOptions>(
      "LoopClosure.enable", [](auto& o) -> auto& { return o.close_loops; },
      "1: after sequential matching, match the pairs a first solve puts close, solve again"));
  AppendOptions(
      LoopClosureOptionTable(), [](auto& o) -> auto& { return o.loop_closure; }, &t);
  return t;
}

}  // namespace

const OptionTable<FeatureOptions>& ExtractionOptionTable() {
  static const OptionTable<FeatureOptions> table = BuildExtractionTable();
  return table;
}

const OptionTable<FeatureOptions>& MatchingOptionTable() {
  static const OptionTable<FeatureOptions> table = [] {
    OptionTable<FeatureOptions> t;
    AppendOptions(
        FeatureMatchingOptionTable(), [](auto& o) -> auto& { return o.matching; }, &t);
    return t;
  }();
  return table;
}

const OptionTable<ReconstructOptions>& ReconstructOptionTable() {
  static const OptionTable<ReconstructOptions> table = BuildReconstructTable();
  return table;
}

void ResolveFeatureOptions(FeatureOptions* options) {
  options->reader.Check();
  options->extraction.Check();
  options->matching.Check();
}

void ResolveReconstructOptions(ReconstructOptions* options) {
  // Each part checked once, by its own resolver; loop closure's ranges are its struct's.
  ResolveFeatureOptions(&options->features);
  // The cameras' focal lengths are the user's only with --ImageReader.camera_params; EXIF's are
  // verified with F and tested by the mapper (FeatureMatchingOptions).
  options->features.matching.essential_matrix_for_given_focal_lengths =
      !options->features.reader.camera_params.empty();
  options->mapper.Check();
  options->loop_closure.Check();
}

}  // namespace ramap
