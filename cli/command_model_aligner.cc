// `ramap model_aligner`: aligns any COLMAP model (ramap's or COLMAP's) to pose priors,
// like `colmap model_aligner --ref_is_gps 1 --alignment_type enu`, robustly: a similarity fitted
// by RANSAC over camera centres, the outlier fixes listed. Writes the model in the priors' metric
// frame, with geo_origin.txt and cameras.geojson when the priors are geodetic. With COLMAP's
// --alignment_type plane, sets the model upright on its principal plane instead (3DGS's
// convert.py). COLMAP's option names are read too, and the output may be the input folder.
#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "options.h"
#include "ramap/estimators/plane_alignment.h"
#include "ramap/estimators/prior_alignment.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_model.h"
#include "ramap/io/geo_export.h"
#include "ramap/io/trajectory.h"
#include "ramap/jobs/pose_prior_loading.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/staged_output.h"

namespace ramap::cli {
namespace {

void WriteAligned(const Reconstruction& model, const std::optional<GeodeticPoint>& origin,
                  const std::string& folder, ModelFormat format) {
  WriteColmapModelAndTrajectory(model, folder, format);
  if (origin) WriteGeoreference(model, *origin, folder);
}

// COLMAP's own options of model_aligner, read into ramap's.
struct ColmapAlignerOptions {
  std::string alignment_type = "enu";  // plane | enu | custom (ecef is not written by ramap)
  std::string ref_images_path;         // NAME X Y Z per line: ramap's prior file
  bool ref_is_gps = true;
  double alignment_max_error = 0;  // m; 0: ramap's default
  bool robust_alignment = true;    // ramap's alignment is always robust
};

// COLMAP's model_aligner --alignment_type plane.
int AlignToPlane(Reconstruction model, const std::string& input_path,
                 const std::string& output_path, ModelFormat format) {
  const Sim3d new_from_old = PrincipalPlaneAlignment(model, input_path);
  TransformReconstruction(new_from_old, &model);
  WriteColmapModelAndTrajectory(model, output_path, format);
  std::cout << "ramap model_aligner: " << model.images.size() << " images and "
            << model.points3D.size()
            << " points set upright on their principal plane (z = 0, +Z towards the cameras) -> "
            << output_path << "\n";
  return 0;
}

struct AlignerCommand {
  std::string input_path, output_path, database_path;
  ModelFormat output_format = ModelFormat::kBinary;
  MapperOptions prior_options;
  ColmapAlignerOptions colmap;
};

// COLMAP's own options of model_aligner, read into ramap's.
void DeclareColmapAlignerOptions(OptionTable<AlignerCommand>& t) {
  t.push_back(ChoiceOption<AlignerCommand>(
      "alignment_type", [](auto& o) -> auto& { return o.colmap.alignment_type; },
      std::vector<std::pair<std::string, std::string>>{
          {"plane", "plane"}, {"enu", "enu"}, {"custom", "custom"}},
      "plane (upright on the points' principal plane) | enu | custom (ECEF models are not "
      "written; use enu)"));
  t.push_back(PathOption<AlignerCommand>(
      "ref_images_path", [](auto& o) -> auto& { return o.colmap.ref_images_path; },
      "as COLMAP's: NAME X Y Z per line (read as --PosePrior.path)"));
  t.push_back(BoolOption<AlignerCommand>(
      "ref_is_gps", [](auto& o) -> auto& { return o.colmap.ref_is_gps; },
      "1: the reference is latitude, longitude, altitude"));
  t.push_back(NumberOption<AlignerCommand>(
      "alignment_max_error", [](auto& o) -> auto& { return o.colmap.alignment_max_error; },
      AtLeast(0), "as --PosePrior.max_alignment_error_m (ignored by plane)"));
  t.push_back(BoolOption<AlignerCommand>(
      "robust_alignment", [](auto& o) -> auto& { return o.colmap.robust_alignment; },
      "accepted: ramap is always robust"));
  t.push_back(NumberOption<AlignerCommand>(
      "robust_alignment_max_error", [](auto& o) -> auto& { return o.colmap.alignment_max_error; },
      AtLeast(0), "as --alignment_max_error"));
}

const OptionTable<AlignerCommand>& AlignerCommandTable() {
  static const OptionTable<AlignerCommand> table = [] {
    OptionTable<AlignerCommand> t;
    t.push_back(Required(PathOption<AlignerCommand>(
        "input_path", [](auto& o) -> auto& { return o.input_path; },
        "COLMAP model folder (.bin or .txt)")));
    t.push_back(Required(PathOption<AlignerCommand>(
        "output_path", [](auto& o) -> auto& { return o.output_path; },
        "folder for the aligned model (may be the input)")));
    t.push_back(PathOption<AlignerCommand>(
        "database_path", [](auto& o) -> auto& { return o.database_path; },
        "COLMAP database whose pose priors are used (without --PosePrior.path)"));
    t.push_back(
        ModelFormatOption<AlignerCommand>([](auto& o) -> auto& { return o.output_format; }));
    // The priors' source and the alignment's --PosePrior.* options, declared with the mapper's;
    // the mapper's uses of the priors (align, use_in_*) are not model_aligner's.
    OptionTable<MapperOptions> priors = MapperOptionSections({"PosePrior"});
    priors.erase(std::remove_if(priors.begin(), priors.end(),
                                [](const OptionDeclaration<MapperOptions>& d) {
                                  return d.Key() == "align" || d.Key().rfind("use_in_", 0) == 0;
                                }),
                 priors.end());
    AppendOptions(
        priors, [](auto& o) -> auto& { return o.prior_options; }, &t);
    DeclareColmapAlignerOptions(t);
    return t;
  }();
  return table;
}

}  // namespace

std::string ModelAlignerOptionsMarkdown() {
  return OptionTableMarkdown(AlignerCommandTable(), AlignerCommand());
}

int RunModelAligner(int argc, char** argv) {
  CLI::App app(
      "Align a COLMAP model to pose priors (GPS): robust similarity, ENU frame; or set "
      "it upright on its principal plane (--alignment_type plane)",
      "ramap model_aligner");
  AlignerCommand command;
  if (const auto code = ParseCommandLine(app, AlignerCommandTable(), &command, argc, argv))
    return *code;
  const std::string& input_path = command.input_path;
  const std::string& output_path = command.output_path;
  const std::string& database_path = command.database_path;
  MapperOptions& prior_options = command.prior_options;
  const ColmapAlignerOptions& colmap = command.colmap;
  PosePriorSource& prior_text = prior_options.prior_source;
  PriorAlignmentOptions& prior_alignment = prior_options.prior_alignment;
  const ModelFormat format = command.output_format;
  if (!colmap.ref_images_path.empty()) {
    prior_text.path = colmap.ref_images_path;
    if (!app.count("--PosePrior.type")) prior_text.type = colmap.ref_is_gps ? "wgs84" : "xyz";
  }
  if (colmap.alignment_max_error > 0) {
    prior_alignment.max_alignment_error_m = colmap.alignment_max_error;
  }
  const bool plane = colmap.alignment_type == "plane";
  if (!plane && prior_text.path.empty() && database_path.empty()) {
    throw InputError("ramap model_aligner",
                     "give --PosePrior.path (or --ref_images_path) or --database_path, or "
                     "--alignment_type plane");
  }
  CheckModelOutputMayReplaceInput("--output_path", output_path, input_path,
                                  {database_path, prior_text.path});

  Reconstruction model = ReadColmapModel(input_path);
  if (plane) return AlignToPlane(std::move(model), input_path, output_path, format);
  // The priors are matched to the model's images by name.
  const FeatureDatabase images = prior_text.path.empty()
                                     ? ModelImagesWithDatabasePriors(model, database_path)
                                     : FeatureDatabase{{}, model.images};
  const LocalizedPriors priors =
      LoadPosePriors(prior_text, images, "ramap model_aligner", &std::cerr);
  const PriorAlignment alignment = AlignModelToPriors(priors.priors, prior_alignment, &model);
  const PriorAlignmentSummary& summary = alignment.summary;
  if (!summary.aligned) {
    throw InputError(input_path, "cannot align the model: " + summary.problem);
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
