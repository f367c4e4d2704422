// `ramap mapper`: a COLMAP database in, COLMAP models out, by motion averaging.
#include <iostream>

#include "mapper_options.h"
#include "mapper_report.h"
#include "options.h"
#include "pose_prior_options.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/colmap_database_schema.h"
#include "ramap/io/database_rigs_priors.h"
#include "ramap/io/point_colors.h"
#include "ramap/pipeline/mapper.h"
#include "ramap/pipeline/mapper_output.h"
#include "ramap/pipeline/stage_log.h"
#include "ramap/util/error.h"
#include "ramap/util/output_policy.h"
#include "ramap/util/timer.h"

namespace ramap::cli {

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
  const ModelFormat format = ModelFormatFromName(output_type, "--output_type");
  CheckFolderOutput("--output_path", output_path, {database_path, image_path, prior_text.path});

  std::ostream* progress = log_level > 0 ? &std::cout : nullptr;
  Timer read_timer;
  const FeatureDatabase database = ReadColmapDatabase(database_path, MapperDatabaseReadOptions());
  const RigSummary rigs = SummarizeRigs(database);
  if (progress) {
    PrintStageLine(*progress, "reading the database", read_timer.ElapsedSeconds(),
                   std::to_string(database.images.size()) + " images, " +
                       std::to_string(database.two_view_geometries.size()) + " verified pairs, " +
                       DatabaseGenerationLabel(database.generation));
  }
  if (rigs.num_multi_camera_frames > 0) {
    std::cerr << "ramap mapper: note: " << rigs.num_multi_camera_frames << " of " << rigs.num_frames
              << " frames hold images of up to " << rigs.max_cameras_per_frame
              << " cameras of one rig; the rig constraints are not used yet: each image is "
                 "averaged on its own\n";
  }
  CheckImageNamesFit(database, format, database_path, "--output_type " + output_type);
  const LocalizedPriors priors = LoadPosePriors(prior_text, database, "ramap mapper", std::cerr);
  MapperResult result = ramap::RunMapper(database, options, database_path, progress, priors.priors);
  if (!image_path.empty()) {
    Timer timer;
    const PointColorSummary colors = ColorModelsFromImages(image_path, &result.reconstructions);
    PrintPointColors(colors, image_path, timer.ElapsedSeconds(), progress, std::cerr);
  }
  const nlohmann::json run = {
      {"command", "mapper"},
      {"database_path", database_path},
      {"image_path", image_path},
      {"database",
       {{"generation", DatabaseGenerationLabel(database.generation)},
        {"num_rigs", rigs.num_rigs},
        {"num_frames", rigs.num_frames},
        {"num_multi_camera_frames", rigs.num_multi_camera_frames},
        {"rig_constraints_used", false}}},
      {"options", MapperOptionsToJson(options)},
      {"pose_priors", PosePriorOptionsToJson(prior_text, options.georegistration)}};
  Timer write_timer;
  WriteMapperOutput(result, output_path, format, run);
  if (progress) {
    PrintStageLine(*progress, "writing the models", write_timer.ElapsedSeconds(), output_path);
  }
  PrintMapperSummary(result.summary, output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
