// `ramap bundle_adjuster --input_path MODEL --output_path MODEL`: COLMAP's command of that name,
// bundle adjustment of a model on its own (nerfstudio runs it after the mapper with
// --BundleAdjustment.refine_principal_point 1). The output may be the input folder: the model is
// read whole first, then its files are replaced by renames.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/trajectory.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/refine/model_bundle_adjustment.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {
namespace {

struct BundleAdjusterCommand {
  std::string input_path, output_path;
  ModelFormat output_format = ModelFormat::kBinary;
  MapperOptions mapper;
};

const OptionTable<BundleAdjusterCommand>& BundleAdjusterCommandTable() {
  static const OptionTable<BundleAdjusterCommand> table = [] {
    OptionTable<BundleAdjusterCommand> t;
    t.push_back(Required(PathOption<BundleAdjusterCommand>(
        "input_path", [](auto& o) -> auto& { return o.input_path; },
        "COLMAP model folder (.bin or .txt)")));
    t.push_back(Required(PathOption<BundleAdjusterCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "folder for the adjusted model (may be the input)")));
    t.push_back(
        ModelFormatOption<BundleAdjusterCommand>([](auto& o) -> auto& { return o.output_format; }));
    // Bundle adjustment's own settings, declared with the mapper's.
    AppendOptions(
        MapperOptionSections(
            {},
            {"BundleAdjustment.max_num_iterations", "BundleAdjustment.loss_scale_px",
             "BundleAdjustment.function_tolerance", "BundleAdjustment.pose_tolerance_deg",
             "BundleAdjustment.max_num_points", "BundleAdjustment.refine_focal_length",
             "BundleAdjustment.refine_principal_point", "BundleAdjustment.refine_extra_params"}),
        [](auto& o) -> auto& { return o.mapper; }, &t);
    return t;
  }();
  return table;
}

}  // namespace

std::string BundleAdjusterOptionsMarkdown() {
  return OptionTableMarkdown(BundleAdjusterCommandTable(), BundleAdjusterCommand());
}

int RunBundleAdjuster(int argc, char** argv) {
  CLI::App app("Bundle adjustment of a COLMAP model: poses, points and the intrinsics asked for",
               "ramap bundle_adjuster");
  BundleAdjusterCommand command;
  if (const auto code = ParseCommandLine(app, BundleAdjusterCommandTable(), &command, argc, argv))
    return *code;
  const std::string& input_path = command.input_path;
  const std::string& output_path = command.output_path;
  MapperOptions& mapper = command.mapper;
  mapper.Check();
  // A model's cameras carry no prior flag, so each would count as guessed: as COLMAP's command,
  // this one refines a principal point only when asked.
  mapper.bundle_adjustment.refine_guessed_principal_point = false;
  mapper.bundle_adjustment.num_threads = mapper.num_threads;
  const BundleAdjustmentOptions& options = mapper.bundle_adjustment;
  const ModelFormat format = command.output_format;
  CheckModelOutputMayReplaceInput("--output_path", output_path, input_path);

  Reconstruction model = ReadColmapModel(input_path);
  const BundleAdjustmentSummary summary = BundleAdjustModel(&model, options, input_path);
  WriteColmapModelAndTrajectory(model, output_path, format);
  std::cout << std::fixed << std::setprecision(3) << "ramap bundle_adjuster: " << summary.num_images
            << " images, " << summary.num_points << " points, RMSE " << summary.initial_rmse_px
            << " -> " << summary.final_rmse_px << " px in " << summary.num_iterations
            << " iterations (" << summary.num_filtered_observations
            << " observations over the error bound detached), " << std::setprecision(2)
            << summary.seconds << " s -> " << output_path << "\n";
  return 0;
}

}  // namespace ramap::cli
