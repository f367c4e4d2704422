// `ramap model_aligner`: georegisters any COLMAP model (ramap's or COLMAP's) to position priors,
// like `colmap model_aligner --ref_is_gps 1 --alignment_type enu`, robustly: a similarity fitted
// by RANSAC over camera centres, the outlier fixes listed. Writes the model in the priors' metric
// frame, with geo_origin.txt and cameras.geojson when the priors are geodetic.
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "options.h"
#include "pose_prior_options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/geo_export.h"
#include "ramap/pipeline/georegistration.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap::cli {
namespace {

void WriteAligned(const Reconstruction& model, const std::optional<GeodeticPoint>& origin,
                  const std::string& folder, ModelFormat format) {
  WriteColmapModel(model, folder, format);
  if (origin) WriteGeoreference(model, *origin, folder);
}

}  // namespace

int RunModelAligner(int argc, char** argv) {
  CLI::App app("Georegister a COLMAP model to position priors (GPS): robust similarity, ENU frame",
               "ramap model_aligner");
  std::string input_path, output_path, database_path, output_type = "BIN";
  app.add_option("--input_path", input_path, "COLMAP model folder (.bin or .txt)")->required();
  app.add_option("--output_path", output_path, "folder for the georegistered model")->required();
  app.add_option("--database_path", database_path,
                 "COLMAP database whose prior_tx/ty/tz are the priors (without --PosePrior.path)");
  app.add_option("--output_type", output_type, "BIN or TXT")->capture_default_str();
  PosePriorOptionText prior_text;
  GeoregistrationOptions georegistration;
  AddPosePriorOptions(app, &prior_text, &georegistration, /*with_uses=*/false);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  const ModelFormat format = ModelFormatFromName(output_type, "--output_type");
  if (prior_text.path.empty() && database_path.empty()) {
    throw InputError("ramap model_aligner", "give --PosePrior.path or --database_path");
  }
  CheckFolderOutput("--output_path", output_path, {input_path, database_path, prior_text.path});

  Reconstruction model = ReadColmapModel(input_path);
  // The priors are matched to the model's images by name.
  const FeatureDatabase images = prior_text.path.empty()
                                     ? ModelImagesWithDatabasePriors(model, database_path)
                                     : FeatureDatabase{{}, model.images};
  const LocalizedPriors priors =
      LoadPosePriors(prior_text, images, "ramap model_aligner", std::cerr);
  const PriorAlignment alignment = GeoregisterModel(priors.priors, georegistration, &model);
  const GeoregistrationSummary& summary = alignment.summary;
  if (!summary.georegistered) {
    throw InputError(input_path, "cannot georegister the model: " + summary.problem);
  }

  if (!std::filesystem::exists(output_path)) {
    StagedPath staged(output_path);
    std::filesystem::create_directories(staged.path());
    WriteAligned(model, priors.priors.origin, staged.path(), format);
    staged.Commit();
  } else {
    WriteAligned(model, priors.priors.origin, output_path, format);
  }
  std::cout << std::fixed << std::setprecision(3) << "ramap model_aligner: " << summary.num_inliers
            << " of " << summary.num_priors << " priors within " << summary.threshold_m
            << " m, RMSE " << summary.rmse_m << " m, scale " << summary.scale
            << " m per model unit -> " << output_path << "\n";
  for (const PriorOutlier& outlier : summary.outliers) {
    std::cout << "  outlier: " << model.images.at(outlier.image_id).name << " prior "
              << outlier.error_m << " m from the aligned centre\n";
  }
  return 0;
}

}  // namespace ramap::cli
