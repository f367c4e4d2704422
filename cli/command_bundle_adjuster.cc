// `ramap bundle_adjuster --input_path MODEL --output_path MODEL`: COLMAP's command of that name,
// bundle adjustment of a model on its own (nerfstudio runs it after the mapper with
// --BundleAdjustment.refine_principal_point 1). The output may be the input folder: the model is
// read whole first, then its files are replaced by renames.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "mapper_options.h"
#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/pipeline/mapper_option_table.h"
#include "ramap/refine/model_bundle_adjustment.h"
#include "ramap/util/output_policy.h"

namespace ramap::cli {

int RunBundleAdjuster(int argc, char** argv) {
  CLI::App app("Bundle adjustment of a COLMAP model: poses, points and the intrinsics asked for",
               "ramap bundle_adjuster");
  std::string input_path, output_path, output_type = "BIN";
  app.add_option("--input_path", input_path, "COLMAP model folder (.bin or .txt)")->required();
  app.add_option("--output_path", output_path, "folder for the adjusted model (may be the input)")
      ->required();
  app.add_option("--output_type", output_type, "BIN or TXT")->capture_default_str();
  // Bundle adjustment's own settings, declared with the mapper's.
  MapperOptions mapper;
  AddOptionTable(
      app,
      MapperOptionSections(
          {}, {"BundleAdjustment.max_num_iterations", "BundleAdjustment.loss_scale_px",
               "BundleAdjustment.function_tolerance", "BundleAdjustment.pose_tolerance_deg",
               "BundleAdjustment.max_num_points", "BundleAdjustment.refine_focal_length",
               "BundleAdjustment.refine_principal_point", "BundleAdjustment.refine_extra_params"}),
      &mapper);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  ResolveMapperOptions(&mapper);
  // A model's cameras carry no prior flag, so each would count as guessed: as COLMAP's command,
  // this one refines a principal point only when asked.
  mapper.bundle_adjustment.refine_guessed_principal_point = false;
  const BundleAdjustmentOptions& options = mapper.bundle_adjustment;
  const ModelFormat format = ModelFormatFromName(output_type, "--output_type");
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
