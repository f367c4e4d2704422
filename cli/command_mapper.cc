// `ramap mapper`: a COLMAP database in, COLMAP models out, by motion averaging.
#include <cmath>
#include <iomanip>
#include <iostream>

#include "mapper_options.h"
#include "options.h"
#include "pose_prior_options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/point_colors.h"
#include "ramap/pipeline/mapper.h"
#include "ramap/pipeline/mapper_output.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/timer.h"

namespace ramap::cli {
namespace {

void PrintSummaryTable(const MapperSummary& s, const std::string& output_path, std::ostream& out) {
  out << "\nramap mapper: " << s.num_registered_images << " of " << s.num_images
      << " images registered in " << s.components.size() << " model(s), " << std::fixed
      << std::setprecision(2) << s.total_seconds << " s -> " << output_path << "\n";
  out << "  model  images  points  reproj(px)  rot.edges  pruned  certified\n";
  for (size_t k = 0; k < s.components.size(); ++k) {
    const MapperComponentSummary& c = s.components[k];
    out << std::setw(7) << k << std::setw(8) << c.num_images << std::setw(8) << c.num_points
        << std::setw(12) << std::setprecision(3) << c.mean_reprojection_error_px << std::setw(11)
        << c.num_rotation_edges << std::setw(8) << c.num_pruned_edges << std::setw(11)
        << (c.rotation_certified ? "yes" : "no") << "\n";
  }
  PrintGeoregistration(s, out);
  // Focal lengths the database did not know, and every camera BA changed.
  for (const CameraIntrinsicsSummary& camera : s.cameras) {
    const CameraCalibration& estimate = camera.view_graph;
    const bool changed = !camera.final_params.empty() && camera.final_params != camera.prior_params;
    if (estimate.camera_id == 0 && !changed) continue;
    out << "  camera " << camera.camera_id << " (" << camera.model << "): focal "
        << std::setprecision(1) << camera.prior_params[0];
    if (estimate.camera_id != 0) {
      out << (estimate.estimated
                  ? " -> " + std::to_string(std::lround(estimate.estimated_focal_px)) +
                        " (view graph, " + std::to_string(estimate.num_pairs) + " pairs)"
                  : " kept (view graph: " + estimate.problem + ")");
    }
    if (changed) out << " -> " << camera.final_params[0] << " (written)";
    out << "\n";
  }
  if (!s.dropped_images.empty()) {
    out << "  not registered (" << s.dropped_images.size() << "):\n";
    for (size_t k = 0; k < s.dropped_images.size() && k < 10; ++k) {
      out << "    " << s.dropped_images[k].what << ": " << s.dropped_images[k].reason << "\n";
    }
    if (s.dropped_images.size() > 10) out << "    ... (all in summary.json)\n";
  }
}

}  // namespace

int RunMapper(int argc, char** argv) {
  CLI::App app("Camera poses and points from a COLMAP database by motion averaging",
               "ramap mapper");
  std::string database_path, image_path, output_path, output_type = "BIN";
  int log_level = 1;
  app.add_option("--database_path", database_path,
                 "COLMAP database (features and verified matches)")
      ->required();
  app.add_option("--image_path", image_path,
                 "folder of the images (optional): points get their colours from it");
  app.add_option("--output_path", output_path, "folder for the models 0, 1, ... and summary.json")
      ->required();
  app.add_option("--output_type", output_type, "BIN or TXT")->capture_default_str();
  app.add_option("--log_level", log_level, "0: summary only, 1: one line per stage")
      ->capture_default_str();
  MapperOptions options;
  MapperOptionText text;
  AddMapperOptions(app, &options, &text);
  PosePriorOptionText prior_text;
  AddPosePriorOptions(app, &prior_text, &options.georegistration, /*with_uses=*/true);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  FinishMapperOptions(text, &options);
  if (output_type != "BIN" && output_type != "TXT") {
    throw InputError("--output_type", "'" + output_type + "' is not BIN or TXT");
  }
  CheckFolderOutput("--output_path", output_path, {database_path, image_path, prior_text.path});

  const FeatureDatabase database = ReadColmapDatabase(database_path);
  const ModelFormat format = output_type == "TXT" ? ModelFormat::kText : ModelFormat::kBinary;
  for (const auto& [image_id, image] : database.images) {
    const std::string problem = ImageNameProblem(image.name, format);
    if (!problem.empty()) {
      throw InputError(database_path, "image " + std::to_string(image_id) + " '" + image.name +
                                          "': " + problem + " (--output_type " + output_type + ")");
    }
  }
  const LocalizedPriors priors = LoadPosePriors(prior_text, database, "ramap mapper", std::cerr);
  MapperResult result = ramap::RunMapper(database, options, database_path,
                                         log_level > 0 ? &std::cout : nullptr, priors.priors);
  if (!image_path.empty()) {
    Timer timer;
    int num_read = 0;
    std::vector<std::string> unreadable;
    for (Reconstruction& reconstruction : result.reconstructions) {
      const PointColorSummary colors = ColorPointsFromImages(image_path, &reconstruction);
      num_read += colors.num_images_read;
      unreadable.insert(unreadable.end(), colors.unreadable_images.begin(),
                        colors.unreadable_images.end());
    }
    if (log_level > 0) {
      PrintStageLine(std::cout, "point colours", timer.ElapsedSeconds(),
                     "from " + std::to_string(num_read) + " images in " + image_path);
    }
    for (const std::string& name : unreadable) {
      std::cerr << "ramap mapper: warning: cannot read " << image_path << "/" << name
                << ": its points keep no colour from it\n";
    }
  }
  const nlohmann::json run = {
      {"command", "mapper"},
      {"database_path", database_path},
      {"image_path", image_path},
      {"options", MapperOptionsToJson(options)},
      {"pose_priors", PosePriorOptionsToJson(prior_text, options.georegistration)}};
  WriteMapperOutput(result, output_path,
                    output_type == "BIN" ? ModelFormat::kBinary : ModelFormat::kText, run);
  PrintSummaryTable(result.summary, output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
