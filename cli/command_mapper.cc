// `ramap mapper`: a COLMAP database in, COLMAP models out, by motion averaging.
#include <iostream>

#include "mapper_options.h"
#include "mapper_report.h"
#include "options.h"
#include "ramap/io/colmap_model.h"
#include "ramap/pipeline/mapper_job.h"

namespace ramap::cli {

int RunMapper(int argc, char** argv) {
  CLI::App app("Camera poses and points from a COLMAP database by motion averaging",
               "ramap mapper");
  MapperJob job;
  std::string output_type = "BIN";
  app.add_option("--database_path", job.database_path,
                 "COLMAP database (features and verified matches)")
      ->required();
  app.add_option("--image_path", job.image_path,
                 "folder of the images (optional): points get their colours from it");
  app.add_option("--output_path", job.output_path,
                 "folder for the models 0, 1, ... and summary.json")
      ->required();
  app.add_option("--output_type", output_type, "BIN or TXT")->capture_default_str();
  const LogLevelOption log_level(app);
  AddMapperOptions(app, &job.options);
  if (const std::optional<int> code = ParseOptions(app, argc, argv)) return *code;
  job.output_format = ModelFormatFromName(output_type, "--output_type");
  const MapperResult result = RunMapperJob(job, log_level.progress(), &std::cerr);
  PrintMapperSummary(result.summary, job.output_path, std::cout);
  return 0;
}

}  // namespace ramap::cli
